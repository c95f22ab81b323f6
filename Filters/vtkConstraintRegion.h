/**
 * @class vtkConstraintRegion
 * @brief Selects a set of positions from its input and gives it a role in a deformation.
 *
 * A space deformation only needs positions (design notes, paper section 3): a region is the set
 * of input points selected by one of the SelectionMode rules, with a Role:
 *  - Handle: the positions move by the handle transform (Translation, Rotation, Scale about Center);
 *  - Fixed: the positions stay in place;
 *  - Planarity, Circularity, Cylinder, FeatureLine, Rigid: geometric constraints (section 6);
 *  - Slip: the positions stay on their (least-squares) rest plane and slide freely within it: a
 *    ground, symmetry, inlet or outlet plane of a CFD domain;
 *  - Symmetric: the positions' displacements are mirror-symmetric about the plane through
 *    SymmetryOrigin with normal SymmetryNormal (a car's or a hull's symmetry plane), so that an
 *    asymmetric handle motion gives a symmetric variant; every position needs its mirror image
 *    among the region's positions;
 *  - Coplanar: the positions of every Coplanar region with the same ConstraintGroup stay on one
 *    common plane (wheel contact patches, a split flange);
 *  - Distance: the two Distance regions of one ConstraintGroup keep the distance of their
 *    centroids (a wheelbase, a bolt spacing), or along DistanceAxis if it is not zero;
 *  - Offset: the positions stay at least MinimumDistance away from the Surface input (port 1; a
 *    fixed reference surface such as an inner part: a minimum wall thickness), a lower bound
 *    active only where violated;
 *  - FromPrimitive (with SelectionMode Primitive): the constraint that keeps the selected
 *    primitive of a vtkPrimitiveDetector output (section 6.3): Planarity for a plane, Cylinder for
 *    a cylinder, FeatureLine (similarity: a sphere stays a sphere, a cone keeps its angle) for a
 *    sphere or a cone.
 *
 * By name: SelectionMode Blocks selects the points of the blocks, patches, patch groups and sets
 * that Blocks names (Adapters/BlockSelection.h: "hull", "motorBike.*", "motorBikeGroup",
 * "/Root/boundary/inlet", a set array "fixed"), so that a case's or a mesh file's own names make
 * one region of many patches: one Handle moves them as one body, about one pivot. A Slip region
 * keeps each of its blocks on its own plane (a ground and the side walls in one region).
 *
 * Cells instead of points: SelectionMode CellLayers selects the cells within NumberOfLayers cell
 * layers of the points of the Surface input (port 1; e.g. the boundary-layer cells along a wall
 * patch of a CFD mesh: layer 1 holds the cells with a point on the surface, layer n + 1 the cells
 * that share a point with layer n). With CellSets on, a constraint role applies to every selected
 * cell on its own (paper section 7.3: each boundary-layer cell rigid): each cell of dimension 2 or
 * 3 with all its points selected (CellLayers: each selected cell) is one constraint set.
 *
 * Split over MPI processes, each selects from its own piece; the pivot (centroid) is that of the
 * positions of all processes, each once, and cell layers grow across pieces (and blocks) through
 * the positions they share.
 *
 * Output: vtkPolyData with the selected positions as vertices, point array
 * "PrescribedDisplacement" (the handle transform's displacement; zero for other roles) and field
 * data "Role" (the Role value; for FromPrimitive the role it stands for), "RoleName" and "Weight"
 * (and for Symmetric "SymmetryPlane": origin and normal; for Coplanar "ConstraintGroup"; for
 * Distance "ConstraintGroup" and "DistanceAxis"; for Offset "MinimumDistance" and
 * "ReferenceTriangles", the Surface input's polygons as triangles, 9 coordinates each).
 * With CellSets, each cell's points in turn (a point of several cells once per cell) and point
 * array "ConstraintSet" (the set a position belongs to); a Slip region in mode Blocks, each
 * block's points in turn and their block in ConstraintSet (negative: -1 - the block's composite
 * id, the same set on every process), and each entry's set arrays (a mesh file's sets: one plane
 * an entry) likewise, entry by entry: a point of two planes slides along both. Plug it into
 * MLSDeform's Regions input.
 */
#ifndef vtkConstraintRegion_h
#define vtkConstraintRegion_h

#include "MLSDeformFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <memory>
#include <string>
#include <vector>

class vtkDoubleArray;
class vtkImplicitFunction;
namespace mlsdeform
{
class Collective;
}

class MLSDEFORMFILTERS_EXPORT vtkConstraintRegion : public vtkPolyDataAlgorithm
{
public:
  static vtkConstraintRegion* New();
  vtkTypeMacro(vtkConstraintRegion, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The values of the table of roles (Vocabulary/RegionRoles.h; the .cxx static_asserts it),
  /// here for the Python wrapping.
  enum Roles
  {
    Handle = 0,
    Fixed,
    Planarity,
    Circularity,
    Cylinder,
    FeatureLine,
    Rigid,
    FromPrimitive,
    Slip, // after FromPrimitive: the values of saved states stay
    Symmetric,
    Coplanar,
    Distance,
    Offset
  };
  static const char* GetRoleName(int role);

  enum SelectionModes
  {
    ImplicitFunction = 0, // points with Region(x) <= 0 (> 0 with InsideOut)
    ArrayRange,           // points whose SelectionArray value (component 0) is within Range
    AllPoints,            // every input point (for use after Extract Selection)
    Primitive,            // points whose PrimitiveIds (vtkPrimitiveDetector) contain PrimitiveId
    CellLayers,           // the points of the cells within NumberOfLayers layers of the Surface input's points
    Blocks                // the points of the blocks, patches, patch groups and sets that Blocks names
  };

  ///@{
  /// The region's role (default Handle).
  vtkSetClampMacro(Role, int, Handle, Offset);
  vtkGetMacro(Role, int);
  ///@}

  ///@{
  /// How the positions are selected (default ImplicitFunction).
  vtkSetClampMacro(SelectionMode, int, ImplicitFunction, Blocks);
  vtkGetMacro(SelectionMode, int);
  ///@}

  ///@{
  /// Mode Blocks: the names of what is selected, each a hierarchy selector ("/Root/boundary/hull"),
  /// a block's name or a pattern of whole names ("motorBike.*"), a patch group of the OpenFOAM case
  /// ("motorBikeGroup"), or a set array (Adapters/BlockSelection.h). An entry that names nothing
  /// is an error.
  void AddBlock(const char* entry);
  void RemoveAllBlocks();
  int GetNumberOfBlocks();
  const char* GetBlock(int i);
  /// After an update in mode Blocks: the names of the blocks it selected whole (this process's
  /// piece), e.g. the patches a group named, in the input's order.
  int GetNumberOfSelectedBlocks();
  const char* GetSelectedBlockName(int i);
  /// Whether a Blocks entry names a block (a patch) called name, or a patch group called group:
  /// for scripts that choose which patches a reader reads (mlsdeform.vtkfoam, mlsdeform.foam).
  static bool NamesBlock(const char* entry, const char* name);
  static bool NamesGroup(const char* entry, const char* group);
  ///@}

  ///@{
  /// Mode Blocks, too: sets of a mesh file by name (the panel lists the arrays the Mesh File
  /// reader marks as its sets), selected with the Blocks entries.
  void AddSet(const char* name);
  void RemoveAllSets();
  ///@}

  ///@{
  /// The primitive of mode Primitive: its id in a vtkPrimitiveDetector's output (default 0). A
  /// vertex on an edge belongs to every primitive of its faces.
  vtkSetClampMacro(PrimitiveId, int, 0, VTK_INT_MAX);
  vtkGetMacro(PrimitiveId, int);
  ///@}

  ///@{
  /// The implicit function (Box, Sphere, Plane, Cylinder, ...) of mode ImplicitFunction.
  void SetRegion(vtkImplicitFunction*);
  vtkGetObjectMacro(Region, vtkImplicitFunction);
  ///@}

  ///@{
  /// Select the outside (Region(x) > 0) instead of the inside (default off).
  vtkSetMacro(InsideOut, bool);
  vtkGetMacro(InsideOut, bool);
  vtkBooleanMacro(InsideOut, bool);
  ///@}

  ///@{
  /// Closed value range of mode ArrayRange; the array is set with SetInputArrayToProcess(0, ...)
  /// or SetSelectionArray.
  vtkSetVector2Macro(Range, double);
  vtkGetVector2Macro(Range, double);
  void SetSelectionArray(const char* name);
  ///@}

  ///@{
  /// Mode CellLayers: how many cell layers from the Surface input are selected (default 3).
  vtkSetClampMacro(NumberOfLayers, int, 1, 1000);
  vtkGetMacro(NumberOfLayers, int);
  ///@}

  /// Mode CellLayers: the surface (port 1) whose points start the layers, e.g. a wall patch.
  void SetSurfaceConnection(vtkAlgorithmOutput* surface) { this->SetInputConnection(1, surface); }

  ///@{
  /// A constraint set per cell instead of one for the region (default off): for the constraint
  /// roles other than Slip (Planarity, Circularity, Cylinder, FeatureLine, Rigid).
  vtkSetMacro(CellSets, bool);
  vtkGetMacro(CellSets, bool);
  vtkBooleanMacro(CellSets, bool);
  ///@}

  ///@{
  /// Handle motion, applied as scale, then rotation about X, Y and Z (degrees), then translation,
  /// about Center (defaults: no motion).
  vtkSetVector3Macro(Translation, double);
  vtkGetVector3Macro(Translation, double);
  vtkSetVector3Macro(Rotation, double);
  vtkGetVector3Macro(Rotation, double);
  vtkSetVector3Macro(Scale, double);
  vtkGetVector3Macro(Scale, double);
  vtkSetVector3Macro(Center, double);
  vtkGetVector3Macro(Center, double);
  ///@}

  ///@{
  /// Rotate and scale about the centroid of the selected positions instead of Center (default on).
  vtkSetMacro(UseCentroid, bool);
  vtkGetMacro(UseCentroid, bool);
  vtkBooleanMacro(UseCentroid, bool);
  ///@}

  /// The point the last update rotated and scaled about (the centroid or Center); the GUI's handle
  /// widget converts between its box and the motion with it.
  vtkGetVector3Macro(Pivot, double);

  /// The kinds of design variable (Adapters/DesignVariables.h; the .cxx static_asserts them).
  enum DesignVariableKinds
  {
    TranslateVariable = 0,
    RotateVariable,
    ScaleVariable,
    LocalVariable
  };

  ///@{
  /// Design variables on a Handle region's motion (Adapters/DesignVariables.h), for design
  /// optimization: each a name, a kind (0 Translate, 1 Rotate, 2 Scale, 3 Local), an axis vector
  /// (its direction times its coefficient: model units, degrees or change of the scale factor per
  /// unit of p; 0 0 0 for Local, whose directions are its control points'), the value p and its
  /// bounds. A value adds to the typed motion (p = 0 leaves it as
  /// typed); the output carries the prescribed displacements' derivative per variable (point
  /// array PrescribedDisplacementDerivatives) and the variables in field data, for MLS Deform's
  /// sensitivities. One name may appear on several regions (one variable moving a pair of
  /// handles): MLS Deform needs the same value and bounds on each. Like the motion, the variables
  /// keep the selection.
  void AddDesignVariable(const char* name, int kind, double ax, double ay, double az, double value, double lower, double upper);
  void RemoveAllDesignVariables();
  int GetNumberOfDesignVariables();
  /// Variable i's name, and its row after the name: kind, axis x, y, z, value, lower, upper
  /// (nullptr and row untouched for an i out of range).
  const char* GetDesignVariableName(int i);
  void GetDesignVariable(int i, double row[7]);
  ///@}

  ///@{
  /// Control points of the Local design variables (Adapters/ControlPoints.h: pyGeo's local shape
  /// variables): each the name of its variable, a position (snapped to the region's nearest
  /// point), a direction times its coefficient (0 0 0: the unit normal of the region's surface
  /// there, out of the mesh) and a line axis (0 0 0: the point alone; otherwise every point of
  /// the region on the line through it along the axis, e.g. the depth of a 2D case). A region
  /// with control points holds only them: its other points are free, so that the surface between
  /// them bends. Its output then carries the point array ControlDirection (each held point's
  /// direction) for drawing. Several control points may share a variable (a mirrored pair).
  void AddControlPoint(const char* variable, double px, double py, double pz, double dx, double dy, double dz, double ax,
    double ay, double az);
  void RemoveAllControlPoints();
  int GetNumberOfControlPoints();
  /// Control point i's variable, and its row after the name: position, direction, line axis.
  const char* GetControlPointVariable(int i);
  void GetControlPoint(int i, double row[9]);
  /// count positions spread evenly over the selection of the last update (all processes'; the
  /// same on every one): farthest-point sampling from the least position, distances measured
  /// across lineAxis unless it is zero. Fills out (3 components) and returns true, or returns
  /// false with the reason in GetControlPointError(), e.g. fewer points than count.
  bool SpreadControlPoints(int count, double ax, double ay, double az, vtkDoubleArray* out);
  const char* GetControlPointError();
  ///@}

  ///@{
  /// Relative weight of this region among the regions of its role (default 1).
  vtkSetClampMacro(Weight, double, 0.0, 1e6);
  vtkGetMacro(Weight, double);
  ///@}

  ///@{
  /// The mirror plane of a Symmetric region: a point on it and its normal (default the plane
  /// y = 0, a vehicle's usual symmetry plane).
  vtkSetVector3Macro(SymmetryOrigin, double);
  vtkGetVector3Macro(SymmetryOrigin, double);
  vtkSetVector3Macro(SymmetryNormal, double);
  vtkGetVector3Macro(SymmetryNormal, double);
  ///@}

  ///@{
  /// The group of a Coplanar or Distance region (default 0): the Coplanar regions of one group
  /// share a plane; the two Distance regions of one group keep their distance.
  vtkSetClampMacro(ConstraintGroup, int, 0, VTK_INT_MAX);
  vtkGetMacro(ConstraintGroup, int);
  ///@}

  ///@{
  /// The axis of a Distance region (default 0, 0, 0: the distance between the two regions'
  /// centroids; otherwise their distance along this direction).
  vtkSetVector3Macro(DistanceAxis, double);
  vtkGetVector3Macro(DistanceAxis, double);
  ///@}

  ///@{
  /// The least distance of an Offset region's points from the Surface input (default 0: the
  /// region's least distance at rest, so that the wall gets no thinner than it is).
  vtkSetClampMacro(MinimumDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MinimumDistance, double);
  ///@}

  ///@{
  /// Set while the handle is being dragged (the GUI's handle box sets it for the drag; default
  /// off). MLS Deform then moves only the surface blocks of a composite input that also has
  /// volume blocks (an OpenFOAM case's patches, not its internal mesh), so that the view keeps up
  /// with the drag; the volume blocks keep their last positions until the update after the drag,
  /// which moves them with no new set-up.
  vtkSetMacro(Dragging, bool);
  vtkGetMacro(Dragging, bool);
  ///@}

  vtkMTimeType GetMTime() override;

  ///@{
  /// The selection is kept while only the motion (Translation, Rotation, Scale, Center,
  /// UseCentroid) or Weight changes; this counts how often the points were selected anew.
  vtkGetMacro(NumberOfSelections, int);
  ///@}

protected:
  vtkConstraintRegion();
  ~vtkConstraintRegion() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Role = Handle;
  int SelectionMode = ImplicitFunction;
  vtkImplicitFunction* Region = nullptr;
  bool InsideOut = false;
  double Range[2] = { 0.0, 1.0 };
  int PrimitiveId = 0;
  int NumberOfLayers = 3;
  bool CellSets = false;
  double Translation[3] = { 0.0, 0.0, 0.0 };
  double Rotation[3] = { 0.0, 0.0, 0.0 };
  double Scale[3] = { 1.0, 1.0, 1.0 };
  double Center[3] = { 0.0, 0.0, 0.0 };
  bool UseCentroid = true;
  double Pivot[3] = { 0.0, 0.0, 0.0 };
  double Weight = 1.0;
  bool Dragging = false;
  int ConstraintGroup = 0;
  double DistanceAxis[3] = { 0.0, 0.0, 0.0 };
  double MinimumDistance = 0.0;
  double SymmetryOrigin[3] = { 0.0, 0.0, 0.0 };
  double SymmetryNormal[3] = { 0.0, 1.0, 0.0 };
  int NumberOfSelections = 0;

private:
  vtkConstraintRegion(const vtkConstraintRegion&) = delete;
  void operator=(const vtkConstraintRegion&) = delete;

  struct Inputs;
  /// The role the output stands for (FromPrimitive: its primitive's), once the settings were
  /// checked against the inputs; throws mlsdeform::InvalidInputException.
  int CheckedRole(const Inputs& in, const mlsdeform::Collective& group);
  /// Selects the positions again when what they depend on changed (SelectionInputs).
  void UpdateSelection(const Inputs& in, const mlsdeform::Collective& group);
  /// The selected positions with their prescribed displacements (the handle motion about the
  /// pivot, with the design variables) and their derivatives, and the role's field data.
  void WriteOutput(vtkPolyData* output, int role, const Inputs& in, const mlsdeform::Collective& group);

  struct Selection;
  std::unique_ptr<Selection> Selected;
  struct DesignVariableList;
  std::unique_ptr<DesignVariableList> Designs;
  std::vector<std::string> BlockNames;    // mode Blocks
  std::vector<std::string> SetNames;      // mode Blocks: a mesh file's sets
  std::vector<std::string> SelectedNames() const; // BlockNames, then SetNames
  std::vector<std::string> SelectedBlocks; // the blocks the last selection took whole
  std::string ControlPointError;           // SpreadControlPoints' last failure

};

#endif
