/**
 * @class vtkPrimitiveDetector
 * @brief Detects planes, cylinders, spheres and cones in a surface mesh (paper section 6.3).
 *
 * The designer need not pick planar or cylindrical regions by hand: this filter proposes them,
 * and a Constraint Region with SelectionMode Primitive keeps the ones chosen. It runs the efficient
 * RANSAC of Schnabel, Wahl and Klein 2007 (octree-localized sampling, scores within Epsilon and
 * NormalThreshold restricted to the largest connected component at ClusterEpsilon, the
 * probabilistic stopping rule) and refines every primitive by a forward search (Atkinson and
 * Riani 2000), then lets every primitive gather again the faces it explains, so that noise
 * neither splits a surface into two primitives nor leaves its most tilted faces out
 * (EfficientRansac.h), on the **face barycenters and face normals** (Fig. 7: vertex normals on sharp edges
 * point along none of the primitives meeting there).
 *
 * Input: vtkPolyData (its polygons), or any other dataset, whose boundary surface is used (a
 * volume mesh's outer faces). Degenerate faces (zero area, fewer than 3 vertices), vertices,
 * lines and triangle strips belong to no primitive. NaN coordinates or no polygon at all: error.
 *
 * Output port 0: the surface with cell arrays PrimitiveId (-1: none) and PrimitiveType (-1 none,
 * 0 plane, 1 cylinder, 2 sphere, 3 cone), point arrays PrimitiveCount (how many primitives a
 * vertex belongs to: every primitive of its faces) and PrimitiveIds (PrimitiveCount ids per
 * vertex, padded with -1, as many components as the largest count), field data PrimitiveTypes
 * (the type of each id).
 * Output port 1: a table with one row per primitive (largest first): Id, Type, TypeCode, Faces,
 * Area, RMSDistance, MaxDistance (of the face barycenters) and the parameters NormalX/Y/Z, Offset
 * (plane n.x = offset), AxisX/Y/Z, CenterX/Y/Z, Radius (cylinder, sphere; a cylinder's center is
 * on its axis), ApexX/Y/Z, Angle (cone: half angle in degrees); NaN where a type has none.
 */
#ifndef vtkPrimitiveDetector_h
#define vtkPrimitiveDetector_h

#include "MLSDeformFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

class MLSDEFORMFILTERS_EXPORT vtkPrimitiveDetector : public vtkPolyDataAlgorithm
{
public:
  static vtkPrimitiveDetector* New();
  vtkTypeMacro(vtkPrimitiveDetector, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The primitive types searched for (default: all).
  vtkSetMacro(DetectPlanes, bool);
  vtkGetMacro(DetectPlanes, bool);
  vtkSetMacro(DetectCylinders, bool);
  vtkGetMacro(DetectCylinders, bool);
  vtkSetMacro(DetectSpheres, bool);
  vtkGetMacro(DetectSpheres, bool);
  vtkSetMacro(DetectCones, bool);
  vtkGetMacro(DetectCones, bool);
  ///@}

  ///@{
  /// Largest distance of a face barycenter from its primitive, as a fraction of the bounding-box
  /// diagonal (default 0.005).
  vtkSetClampMacro(Epsilon, double, 1e-9, 1.0);
  vtkGetMacro(Epsilon, double);
  ///@}

  ///@{
  /// Faces of one primitive are connected through gaps below this fraction of the bounding-box
  /// diagonal (default 0.02); farther patches of the same surface become separate primitives.
  vtkSetClampMacro(ClusterEpsilon, double, 1e-9, 1.0);
  vtkGetMacro(ClusterEpsilon, double);
  ///@}

  ///@{
  /// Largest angle between a face normal and its primitive's normal, degrees (default 20); a
  /// primitive whose faces scatter more (noise) admits up to 4 times their RMS angle.
  vtkSetClampMacro(NormalThreshold, double, 0.01, 90.0);
  vtkGetMacro(NormalThreshold, double);
  ///@}

  ///@{
  /// Fewest faces of a primitive (default 10).
  vtkSetClampMacro(MinimumSupport, int, 3, VTK_INT_MAX);
  vtkGetMacro(MinimumSupport, int);
  ///@}

  ///@{
  /// Probability that a primitive of MinimumSupport faces is found before the search stops
  /// (default 0.95; CGAL's "probability" parameter is one minus this).
  vtkSetClampMacro(Probability, double, 0.01, 0.999999);
  vtkGetMacro(Probability, double);
  ///@}

  ///@{
  /// Seed of the random sampling: the same seed gives the same primitives, on any number of
  /// threads (default 0).
  vtkSetClampMacro(RandomSeed, int, 0, VTK_INT_MAX);
  vtkGetMacro(RandomSeed, int);
  ///@}

protected:
  vtkPrimitiveDetector();
  ~vtkPrimitiveDetector() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool DetectPlanes = true;
  bool DetectCylinders = true;
  bool DetectSpheres = true;
  bool DetectCones = true;
  double Epsilon = 0.005;
  double ClusterEpsilon = 0.02;
  double NormalThreshold = 20.0;
  int MinimumSupport = 10;
  double Probability = 0.95;
  int RandomSeed = 0;

private:
  vtkPrimitiveDetector(const vtkPrimitiveDetector&) = delete;
  void operator=(const vtkPrimitiveDetector&) = delete;
};

#endif
