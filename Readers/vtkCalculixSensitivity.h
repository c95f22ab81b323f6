/**
 * @class vtkCalculixSensitivity
 * @brief The exact shape gradient dJ/dX at every node of a CalculiX deck, from its ccx run (and,
 * for responses that need it, one adjoint run), for DesignVariables.totalSensitivity.
 *
 * For K(X) u = f with the supports of the deck's static step, a response J(u, X) and the adjoint
 * lambda (K lambda = dJ/du, the supports homogeneous), dJ/dX = dJ/dX|_u - lambda^T d(K u)/dX
 * + lambda^T df/dX (point loads do not depend on X; gravity and pressure do), with d(K u)/dX and df/dX
 * element by element as ccx integrates the
 * element (Filters/Core/Structural/ShapeSensitivity.h): three components at every node, interior
 * and midside nodes too. The responses:
 * - Compliance: f . u, the loads' work: point loads, pressures and gravity (self-adjoint: lambda = u, no
 *   adjoint run);
 * - Mass, Volume: of the elements of ResponseSet (empty: all), densities from *DENSITY (no u);
 * - Displacement: sum over the nodes of ResponseSet of Direction . u (an adjoint run);
 * - DisplacementNorm: sqrt(sum over the nodes of ResponseSet of |u|^2), ccx's ALL-DISP (an
 *   adjoint run; its loads need u);
 * - Stress: the KS aggregate of the von Mises stresses at the integration points of the elements
 *   of ResponseSet (empty: all), m + (S / rho) ln sum exp(rho (sigma_g - m) / S) with m the
 *   largest, S the ReferenceStress and rho the KSWeight: between m and m + S ln(N) / rho (an
 *   adjoint run; its loads need u).
 * The deck: solid elements C3D4, C3D10, C3D8, C3D20, C3D20R, C3D6, C3D15, isotropic linear elastic
 * materials, one linear static step with *BOUNDARY, *CLOAD and *DLOAD (P1 to P6 on element faces,
 * GRAV); anything else is refused naming
 * the keyword (Formats/Abaqus/CalculixAnalysis.h).
 */
#ifndef vtkCalculixSensitivity_h
#define vtkCalculixSensitivity_h

#include "MLSDeformReadersModule.h"
#include "vtkObject.h"

#include <memory>
#include <string>

class vtkDoubleArray;
class vtkIdTypeArray;

class MLSDEFORMREADERS_EXPORT vtkCalculixSensitivity : public vtkObject
{
public:
  static vtkCalculixSensitivity* New();
  vtkTypeMacro(vtkCalculixSensitivity, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Responses
  {
    Compliance = 0,
    Mass = 1,
    Volume = 2,
    Displacement = 3,
    DisplacementNorm = 4,
    Stress = 5
  };

  ///@{
  /// The deck ccx ran (the design's variant deck).
  vtkSetStdStringFromCharMacro(DeckFileName);
  vtkGetCharFromStdStringMacro(DeckFileName);
  ///@}

  ///@{
  /// ccx's result of the deck (JOB.frd with U: *NODE FILE, U in the static step; *NODE FILE,
  /// DOUBLE writes it in full precision, where the ASCII file has 6 digits, which limit dJ/dX to
  /// about 1e-3 of its largest component on a fine mesh).
  vtkSetStdStringFromCharMacro(ResultFileName);
  vtkGetCharFromStdStringMacro(ResultFileName);
  ///@}

  ///@{
  /// ccx's result of the adjoint deck (AdjointLoads' load case), for the responses that need it.
  vtkSetStdStringFromCharMacro(AdjointResultFileName);
  vtkGetCharFromStdStringMacro(AdjointResultFileName);
  ///@}

  ///@{
  /// The response (Responses; default Compliance).
  vtkSetClampMacro(Response, int, Compliance, Stress);
  vtkGetMacro(Response, int);
  ///@}

  ///@{
  /// The response's element set (Mass, Volume, Stress; empty: every element) or node set
  /// (Displacement, DisplacementNorm).
  vtkSetStdStringFromCharMacro(ResponseSet);
  vtkGetCharFromStdStringMacro(ResponseSet);
  ///@}

  ///@{
  /// Stress's aggregation: the KS weight rho (default 50) and the reference stress S (default 1,
  /// in the deck's units, e.g. the yield stress): J exceeds the largest stress by at most
  /// S ln(N) / rho.
  vtkSetClampMacro(KSWeight, double, 1e-6, 1e6);
  vtkGetMacro(KSWeight, double);
  vtkSetClampMacro(ReferenceStress, double, 1e-300, 1e300);
  vtkGetMacro(ReferenceStress, double);
  ///@}

  ///@{
  /// Displacement's direction (default 0, 0, 1; not normalized: J is linear in it).
  vtkSetVector3Macro(Direction, double);
  vtkGetVector3Macro(Direction, double);
  ///@}

  /// Whether the response needs an adjoint run (Displacement, DisplacementNorm, Stress).
  bool NeedsAdjoint() const;

  /// The adjoint load case dJ/du: node ids and the three components at each (only nodes with a
  /// load), and the supports' node ids and degrees of freedom (1 to 3), to be written as the
  /// adjoint deck's *CLOAD and homogeneous *BOUNDARY. Reads the deck (and the result where
  /// dJ/du needs u). False with LastError on failure.
  bool ComputeAdjointLoads();
  vtkIdTypeArray* GetAdjointLoadNodes();
  vtkDoubleArray* GetAdjointLoads();
  vtkIdTypeArray* GetSupportNodes();
  vtkIdTypeArray* GetSupportDofs();

  /// J and dJ/dX from the deck, its result and (where needed) the adjoint result. False with
  /// LastError on failure (the error also goes to the output window).
  bool Compute();
  /// J alone (no adjoint result needed; the gradient left empty), as for central differences.
  bool ComputeValue();
  double GetValue() const;
  /// dJ/dX, 3 components a node, in the deck's node order (GetNodeIds).
  vtkDoubleArray* GetGradient();
  vtkIdTypeArray* GetNodeIds();
  /// The deck's node coordinates, in that order.
  vtkDoubleArray* GetNodeCoordinates();

  /// Why the last call failed, "" when it did not.
  const char* GetLastError() const { return this->LastError.c_str(); }

protected:
  vtkCalculixSensitivity();
  ~vtkCalculixSensitivity() override;

private:
  vtkCalculixSensitivity(const vtkCalculixSensitivity&) = delete;
  void operator=(const vtkCalculixSensitivity&) = delete;

  struct Internals;
  std::unique_ptr<Internals> State;
  std::string DeckFileName, ResultFileName, AdjointResultFileName, ResponseSet, LastError;
  int Response = Compliance;
  double Direction[3] = { 0, 0, 1 };
  double KSWeight = 50, ReferenceStress = 1;
  bool ValueOnly = false;
};

#endif
