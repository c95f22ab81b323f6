#include "vtkCalculixSensitivity.h"

#include "Abaqus/CalculixAnalysis.h"
#include "Structural/ShapeSensitivity.h"

#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

using mlsdeform::PointList;
using mlsdeform::Vec3;
namespace abaqus = mlsformats::abaqus;

vtkStandardNewMacro(vtkCalculixSensitivity);

struct vtkCalculixSensitivity::Internals
{
  vtkNew<vtkDoubleArray> Gradient, AdjointLoads, NodeCoordinates;
  vtkNew<vtkIdTypeArray> NodeIds, AdjointLoadNodes, SupportNodes, SupportDofs;
  double Value = 0;
};

namespace
{
// The deck's solid elements with their materials (elements: all of them, or those listed), and
// the materials as the core takes them.
mlsdeform::SolidMesh solidMesh(const abaqus::CalculixAnalysis& a, const std::vector<long>* only)
{
  std::vector<char> kept;
  if (only)
  {
    kept.assign(a.elementMaterial.size(), 0);
    for (long e : *only)
    {
      kept[e] = 1;
    }
  }
  mlsdeform::SolidMesh mesh;
  long e = 0;
  std::vector<int> nodes;
  for (const mlsformats::ElementBlock& block : a.deck.mesh.blocks)
  {
    mlsdeform::SolidElement type;
    if (!mlsdeform::solidElementOf(block.name, type))
    {
      throw std::runtime_error("element type " + block.name + " is not supported by the exact shape derivatives (solids C3D4, "
                               "C3D10, C3D8, C3D20, C3D20R, C3D6, C3D15)");
    }
    const int n = mlsdeform::nodeCount(type);
    for (std::size_t k = 0; k < block.ids.size(); ++k, ++e)
    {
      if (only && !kept[e])
      {
        continue;
      }
      nodes.clear();
      for (int c = 0; c < n; ++c)
      {
        nodes.push_back(static_cast<int>(a.nodeIndex(block.nodes[k * n + c])));
      }
      mesh.add(type, nodes.data(), a.elementMaterial[e]);
    }
  }
  return mesh;
}

PointList deckPoints(const abaqus::CalculixAnalysis& a)
{
  PointList X(a.deck.mesh.nodeIds.size());
  for (std::size_t n = 0; n < X.size(); ++n)
  {
    X[n] = Vec3(a.deck.mesh.xyz[3 * n], a.deck.mesh.xyz[3 * n + 1], a.deck.mesh.xyz[3 * n + 2]);
  }
  return X;
}

// The displacements of a ccx result, in the deck's node order: a result of this deck (every node
// and no other, at the deck's coordinates to the .frd's precision: 6 digits in ASCII).
PointList displacements(const abaqus::CalculixAnalysis& a, const PointList& X, const std::string& path, const char* what)
{
  if (path.empty())
  {
    throw std::runtime_error(std::string("no ") + what + " file: give ccx's result (JOB.frd)");
  }
  const abaqus::FrdDisplacements frd = abaqus::readFrdDisplacements(path);
  const std::size_t n = a.deck.mesh.nodeIds.size();
  if (frd.displacements.size() != n || frd.coordinates.size() != n)
  {
    throw std::runtime_error(path + " holds " + std::to_string(frd.displacements.size()) + " nodes' displacements, the deck " +
      std::to_string(n) + " nodes: a result of another mesh");
  }
  double scale = 0;
  for (const Vec3& x : X)
  {
    scale = std::max(scale, x.cwiseAbs().maxCoeff());
  }
  PointList u(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::int64_t id = a.deck.mesh.nodeIds[k];
    const auto found = frd.displacements.find(id);
    const auto at = frd.coordinates.find(id);
    if (found == frd.displacements.end() || at == frd.coordinates.end())
    {
      throw std::runtime_error(path + " has no displacement of node " + std::to_string(id) + ": a result of another mesh");
    }
    // E12.5: a coordinate rounded by at most 5e-6 of its size
    if ((Vec3(at->second[0], at->second[1], at->second[2]) - X[k]).cwiseAbs().maxCoeff() > 1e-5 * (scale > 0 ? scale : 1.0))
    {
      throw std::runtime_error(path + " is a result of another shape: node " + std::to_string(id) + " is not where the deck " +
        "has it (run ccx on this deck)");
    }
    u[k] = Vec3(found->second[0], found->second[1], found->second[2]);
  }
  return u;
}

std::vector<mlsdeform::IsotropicElastic> elastic(const abaqus::CalculixAnalysis& a)
{
  std::vector<mlsdeform::IsotropicElastic> materials;
  for (const abaqus::IsotropicMaterial& m : a.materials)
  {
    materials.push_back({ m.youngs, m.poisson });
  }
  return materials;
}
} // namespace

vtkCalculixSensitivity::vtkCalculixSensitivity()
  : State(new Internals)
{
  this->State->Gradient->SetName("dJdX");
  this->State->Gradient->SetNumberOfComponents(3);
  this->State->AdjointLoads->SetNumberOfComponents(3);
  this->State->NodeCoordinates->SetNumberOfComponents(3);
  this->State->NodeIds->SetName("NodeId");
}

vtkCalculixSensitivity::~vtkCalculixSensitivity() = default;

void vtkCalculixSensitivity::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DeckFileName: " << this->DeckFileName << "\n"
     << indent << "ResultFileName: " << this->ResultFileName << "\n"
     << indent << "AdjointResultFileName: " << this->AdjointResultFileName << "\n"
     << indent << "Response: " << this->Response << " (" << this->ResponseSet << ")\n";
}

bool vtkCalculixSensitivity::NeedsAdjoint() const
{
  return this->Response == Displacement || this->Response == DisplacementNorm || this->Response == Stress;
}

namespace
{
// The elements of the set, or all of them.
std::vector<long> elementsOf(const abaqus::CalculixAnalysis& a, const std::string& set)
{
  if (!set.empty())
  {
    return a.elementSet(set);
  }
  std::vector<long> all(a.elementMaterial.size());
  for (std::size_t e = 0; e < all.size(); ++e)
  {
    all[e] = static_cast<long>(e);
  }
  return all;
}

// dJ/du at every node (zero where J does not depend on the node's u): the adjoint load case
PointList adjointLoads(vtkCalculixSensitivity& self, const abaqus::CalculixAnalysis& a, const PointList& X)
{
  PointList dJdu(X.size(), Vec3::Zero());
  const std::string set = self.GetResponseSet();
  if (self.GetResponse() == vtkCalculixSensitivity::Stress)
  {
    const PointList u = displacements(a, X, self.GetResultFileName(), "result");
    mlsdeform::meshStressAggregate(solidMesh(a, nullptr), X, u, elastic(a), elementsOf(a, set), self.GetKSWeight(),
      self.GetReferenceStress(), &dJdu, nullptr);
    return dJdu;
  }
  if (set.empty())
  {
    throw std::runtime_error("a displacement response needs the node set it measures (ResponseSet)");
  }
  const std::vector<std::size_t> nodes = a.nodeSet(set);
  const Vec3 direction(self.GetDirection()[0], self.GetDirection()[1], self.GetDirection()[2]);
  PointList u;
  double norm = 0;
  if (self.GetResponse() == vtkCalculixSensitivity::DisplacementNorm)
  {
    u = displacements(a, X, self.GetResultFileName(), "result");
    for (std::size_t n : nodes)
    {
      norm += u[n].squaredNorm();
    }
    norm = std::sqrt(norm);
  }
  else if (!(direction.norm() > 0) || !direction.allFinite())
  {
    throw std::runtime_error("the displacement response's Direction is zero or not finite");
  }
  for (std::size_t n : nodes)
  {
    // the direction, or u_i / |u|_S for the norm
    dJdu[n] = self.GetResponse() == vtkCalculixSensitivity::DisplacementNorm ? (norm > 0 ? Vec3(u[n] / norm) : Vec3::Zero()) : direction;
  }
  return dJdu;
}
} // namespace

bool vtkCalculixSensitivity::ComputeAdjointLoads()
{
  this->LastError.clear();
  try
  {
    if (!this->NeedsAdjoint())
    {
      throw std::runtime_error("the response needs no adjoint run (compliance is self-adjoint; mass and volume do not depend on u)");
    }
    const abaqus::CalculixAnalysis a = abaqus::readCalculixAnalysis(this->DeckFileName);
    const PointList X = deckPoints(a);
    const PointList dJdu = adjointLoads(*this, a, X);
    std::vector<std::size_t> loaded;
    for (std::size_t n = 0; n < dJdu.size(); ++n)
    {
      if (!dJdu[n].isZero(0))
      {
        loaded.push_back(n);
      }
    }
    if (loaded.empty())
    {
      throw std::runtime_error(this->Response == Stress ? "the element set has no stress: the stress aggregate has no derivative"
                                                        : "the node set " + this->ResponseSet +
            " does not move: the norm of its displacements has no derivative");
    }
    this->State->AdjointLoadNodes->SetNumberOfTuples(static_cast<vtkIdType>(loaded.size()));
    this->State->AdjointLoads->SetNumberOfTuples(static_cast<vtkIdType>(loaded.size()));
    for (std::size_t k = 0; k < loaded.size(); ++k)
    {
      const Vec3& load = dJdu[loaded[k]];
      this->State->AdjointLoadNodes->SetValue(static_cast<vtkIdType>(k), a.deck.mesh.nodeIds[loaded[k]]);
      this->State->AdjointLoads->SetTuple3(static_cast<vtkIdType>(k), load[0], load[1], load[2]);
    }
    this->State->SupportNodes->SetNumberOfTuples(static_cast<vtkIdType>(a.supports.size()));
    this->State->SupportDofs->SetNumberOfTuples(static_cast<vtkIdType>(a.supports.size()));
    for (std::size_t k = 0; k < a.supports.size(); ++k)
    {
      this->State->SupportNodes->SetValue(static_cast<vtkIdType>(k), a.deck.mesh.nodeIds[a.supports[k].node]);
      this->State->SupportDofs->SetValue(static_cast<vtkIdType>(k), a.supports[k].dof + 1);
    }
    return true;
  }
  catch (const std::exception& e)
  {
    this->LastError = e.what();
    vtkErrorMacro(<< this->LastError);
    return false;
  }
}

bool vtkCalculixSensitivity::Compute()
{
  this->LastError.clear();
  try
  {
    const abaqus::CalculixAnalysis a = abaqus::readCalculixAnalysis(this->DeckFileName);
    const PointList X = deckPoints(a);
    PointList gradient;
    double value = 0;
    if (this->Response == Mass || this->Response == Volume)
    {
      std::vector<long> set;
      if (!this->ResponseSet.empty())
      {
        set = a.elementSet(this->ResponseSet);
      }
      std::vector<double> weight;
      for (const abaqus::IsotropicMaterial& m : a.materials)
      {
        weight.push_back(this->Response == Mass ? m.density : 1.0);
      }
      if (this->Response == Mass && std::all_of(weight.begin(), weight.end(), [](double w) { return w == 0; }))
      {
        throw std::runtime_error("the deck's materials have no *DENSITY: the mass is zero and does not depend on the design");
      }
      value = mlsdeform::meshVolume(solidMesh(a, this->ResponseSet.empty() ? nullptr : &set), X, weight, this->ValueOnly ? nullptr : &gradient);
    }
    else
    {
      const PointList u = displacements(a, X, this->ResultFileName, "result");
      const mlsdeform::SolidMesh mesh = solidMesh(a, nullptr);
      // gravity: the body force per unit volume of each element, rho g
      std::vector<Vec3> body(a.elementMaterial.size(), Vec3::Zero());
      bool gravity = false;
      for (std::size_t e = 0; e < body.size(); ++e)
      {
        const auto& g = a.elementAcceleration[e];
        body[e] = a.materials[a.elementMaterial[e]].density * Vec3(g[0], g[1], g[2]);
        gravity = gravity || !body[e].isZero(0);
      }
      std::vector<mlsdeform::FacePressure> pressures;
      for (const abaqus::ElementPressure& p : a.pressures)
      {
        pressures.push_back({ p.element, p.face, p.pressure });
      }
      PointList lambda, stressGradient;
      if (this->Response == Compliance)
      {
        for (const abaqus::NodeDof& load : a.loads)
        {
          value += load.value * u[load.node][load.dof];
        }
        if (gravity)
        {
          value += mlsdeform::meshBodyWork(mesh, X, u, body, nullptr);
        }
        if (!pressures.empty())
        {
          value += mlsdeform::meshPressureWork(mesh, X, u, pressures, nullptr);
        }
        if (a.loads.empty() && !gravity && pressures.empty())
        {
          throw std::runtime_error("the static step has no loads (*CLOAD, *DLOAD pressure, gravity with a *DENSITY): the compliance "
                                   "is zero and does not depend on the design");
        }
        lambda = u; // K lambda = f: lambda = u
      }
      else if (this->Response == Stress)
      {
        // dJ/dX at fixed u: the stresses' gradients move with the nodes
        value = mlsdeform::meshStressAggregate(mesh, X, u, elastic(a), elementsOf(a, this->ResponseSet), this->KSWeight,
          this->ReferenceStress, nullptr, this->ValueOnly ? nullptr : &stressGradient);
      }
      else
      {
        const std::vector<std::size_t> nodes = a.nodeSet(this->ResponseSet);
        const Vec3 direction(this->Direction[0], this->Direction[1], this->Direction[2]);
        for (std::size_t n : nodes)
        {
          value += this->Response == Displacement ? direction.dot(u[n]) : u[n].squaredNorm();
        }
        if (this->Response == DisplacementNorm)
        {
          value = std::sqrt(value);
        }
      }
      if (this->Response != Compliance && !this->ValueOnly)
      {
        lambda = displacements(a, X, this->AdjointResultFileName, "adjoint result");
        // K symmetric: lambda . f = lambda^T K u = u^T K lambda = u . dJ/du where the supports hold
        // zero (a nonzero support adds its reaction): the adjoint of this response and design
        const PointList dJdu = adjointLoads(*this, a, X);
        double lambdaF = gravity ? mlsdeform::meshBodyWork(mesh, X, lambda, body, nullptr) : 0.0, uG = 0;
        lambdaF += pressures.empty() ? 0.0 : mlsdeform::meshPressureWork(mesh, X, lambda, pressures, nullptr);
        for (const abaqus::NodeDof& load : a.loads)
        {
          lambdaF += load.value * lambda[load.node][load.dof];
        }
        for (std::size_t n = 0; n < u.size(); ++n)
        {
          uG += u[n].dot(dJdu[n]);
        }
        const bool homogeneous = std::all_of(a.supports.begin(), a.supports.end(), [](const abaqus::NodeDof& s) { return s.value == 0; });
        // (1e-4: an adjoint result written in ASCII has six digits)
        if (homogeneous && !(std::abs(lambdaF - uG) <= 1e-4 * (std::abs(lambdaF) + std::abs(uG))))
        {
          throw std::runtime_error(this->AdjointResultFileName + " is not the adjoint of this response and design (lambda . f = " +
            std::to_string(lambdaF) + ", u . dJ/du = " + std::to_string(uG) + "): run ccx on the adjoint deck written for them");
        }
      }
      // dJ/dX = dJ/dX|_u + lambda^T (df/dX - d(K u)/dX): point loads do not depend on X, gravity
      // and pressure do; the compliance f . u has dJ/dX|_u = u^T df/dX, with lambda = u
      if (!this->ValueOnly)
      {
        mlsdeform::meshWork(mesh, X, u, lambda, elastic(a), &gradient);
      }
      for (std::size_t n = 0; n < gradient.size(); ++n)
      {
        gradient[n] = (stressGradient.empty() ? Vec3::Zero() : stressGradient[n]) - gradient[n];
      }
      // the loads that move with the shape: gravity (the volumes), pressure (the faces' areas)
      const double times = this->Response == Compliance ? 2.0 : 1.0;
      for (int kind = 0; kind < 2 && !this->ValueOnly; ++kind)
      {
        if (kind == 0 ? !gravity : pressures.empty())
        {
          continue;
        }
        PointList load;
        if (kind == 0)
        {
          mlsdeform::meshBodyWork(mesh, X, lambda, body, &load);
        }
        else
        {
          mlsdeform::meshPressureWork(mesh, X, lambda, pressures, &load);
        }
        for (std::size_t n = 0; n < gradient.size(); ++n)
        {
          gradient[n] += times * load[n];
        }
      }
    }
    this->State->Value = value;
    this->State->Gradient->SetNumberOfTuples(static_cast<vtkIdType>(gradient.size()));
    this->State->NodeIds->SetNumberOfTuples(static_cast<vtkIdType>(gradient.size()));
    this->State->NodeCoordinates->SetNumberOfTuples(static_cast<vtkIdType>(gradient.size()));
    for (std::size_t n = 0; n < gradient.size(); ++n)
    {
      this->State->Gradient->SetTuple3(static_cast<vtkIdType>(n), gradient[n][0], gradient[n][1], gradient[n][2]);
      this->State->NodeIds->SetValue(static_cast<vtkIdType>(n), a.deck.mesh.nodeIds[n]);
      this->State->NodeCoordinates->SetTuple3(static_cast<vtkIdType>(n), X[n][0], X[n][1], X[n][2]);
    }
    return true;
  }
  catch (const std::exception& e)
  {
    this->LastError = e.what();
    vtkErrorMacro(<< this->LastError);
    return false;
  }
}

bool vtkCalculixSensitivity::ComputeValue()
{
  this->ValueOnly = true;
  const bool computed = this->Compute();
  this->ValueOnly = false;
  return computed;
}

double vtkCalculixSensitivity::GetValue() const
{
  return this->State->Value;
}

vtkDoubleArray* vtkCalculixSensitivity::GetGradient()
{
  return this->State->Gradient;
}

vtkIdTypeArray* vtkCalculixSensitivity::GetNodeIds()
{
  return this->State->NodeIds;
}

vtkDoubleArray* vtkCalculixSensitivity::GetNodeCoordinates()
{
  return this->State->NodeCoordinates;
}

vtkIdTypeArray* vtkCalculixSensitivity::GetAdjointLoadNodes()
{
  return this->State->AdjointLoadNodes;
}

vtkDoubleArray* vtkCalculixSensitivity::GetAdjointLoads()
{
  return this->State->AdjointLoads;
}

vtkIdTypeArray* vtkCalculixSensitivity::GetSupportNodes()
{
  return this->State->SupportNodes;
}

vtkIdTypeArray* vtkCalculixSensitivity::GetSupportDofs()
{
  return this->State->SupportDofs;
}
