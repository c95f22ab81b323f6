// What a CalculiX deck's linear static analysis is, for its exact shape derivatives
// (vtkCalculixSensitivity, Filters/Core/Structural): the elements' materials (isotropic linear
// elastic), the supports, the point loads, the pressures on element faces and the gravity of its
// static step. Anything the derivatives do not cover is refused naming the keyword: NLGEOM, other
// procedures, contact, shells, beams, constraints, other materials and loads, never silently
// approximated.
#pragma once

#include "Abaqus/AbaqusDeck.h"
#include "Common/IdIndex.h"

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mlsformats
{
namespace abaqus
{
/// A displacement component held (a support) or a force on it (a point load).
struct NodeDof
{
  std::size_t node; // index into mesh.nodeIds
  int dof;          // 0, 1, 2
  double value;
};

/// A pressure on face `face` (1 ..) of an element (its index over the blocks): *DLOAD Pn.
struct ElementPressure
{
  long element;
  int face;
  double pressure;
};

/// A *MATERIAL with its *ELASTIC (isotropic) and *DENSITY (0 where the deck has none).
struct IsotropicMaterial
{
  std::string name;
  double youngs = 0, poisson = 0, density = 0;
};

struct CalculixAnalysis
{
  Deck deck;
  std::vector<IsotropicMaterial> materials;
  /// Per element of the deck's blocks, in their order: its material (by *SOLID SECTION), -1 for
  /// an element without a section.
  std::vector<int> elementMaterial;
  std::vector<NodeDof> supports; // the static step's *BOUNDARY (the model's and the step's)
  std::vector<NodeDof> loads;    // the static step's *CLOAD
  /// Per element (over the blocks): the static step's gravity (*DLOAD GRAV), the acceleration's
  /// magnitude times its direction (the body force is the density times it); zero without.
  std::vector<std::array<double, 3>> elementAcceleration;
  /// The static step's pressures (*DLOAD P1 .. P6), in the deck's order.
  std::vector<ElementPressure> pressures;
  /// The node indices of a node set, the element indices (over the blocks) of an element set: by
  /// name (any case); throw std::runtime_error naming the sets there are when it does not exist.
  std::vector<std::size_t> nodeSet(const std::string& name) const;
  std::vector<long> elementSet(const std::string& name) const;
  /// The node's index; throws std::runtime_error when the deck has no such node.
  std::size_t nodeIndex(std::int64_t id) const;

  /// The element's index over the blocks; throws std::runtime_error when there is none.
  long elementIndex(std::int64_t id) const;

  std::optional<IdIndex> IndexOfNode, IndexOfElement; // of deck.mesh.nodeIds, of the blocks' element ids
};

/// Reads the deck and its analysis. Throws FileError (reading) or std::runtime_error naming the
/// keyword and where it stands (what the analysis does not support).
CalculixAnalysis readCalculixAnalysis(const std::string& path);

/// What a ccx result file (.frd) holds of a static step: the node coordinates and the last
/// nodal displacement block (DISP: the last step's), by node id. ASCII (*NODE FILE: 6
/// significant digits) and binary (*NODE FILE, DOUBLE: full precision; *NODE OUTPUT: floats).
struct FrdDisplacements
{
  std::map<std::int64_t, std::array<double, 3>> coordinates, displacements;
};

/// Throws FileError when the file or its blocks are missing, naming what the deck needs (*NODE
/// FILE with U).
FrdDisplacements readFrdDisplacements(const std::string& path);
} // namespace abaqus
} // namespace mlsformats
