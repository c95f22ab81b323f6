// OpenFOAM's checkMesh face measures (section 7.3) against values computed by hand.
#include "../TestHarness.h"
#include "Quality/FaceQuality.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

using namespace mlsdeform;

// Every bound here is round-off: the exact values are known, and the measures are a few dozen
// floating-point operations on coordinates of size <= 2, each rounding by at most eps = 2.2e-16
// relative. Coordinates and results that are dyadic rationals (0.5, 0.25, 2, ...) are computed
// exactly; for the others, k operations on values of size v give at most about k eps v.

namespace
{
// The six quadrilateral faces of the box [x0, x1] x [0, 1] x [0, 1] with corner points appended.
std::vector<std::vector<int>> boxFaces(PointList& points, double x0, double x1)
{
  const int b = static_cast<int>(points.size());
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        points.push_back(Vec3(i ? x1 : x0, j, k));
  auto v = [b](int i, int j, int k) { return b + i + 2 * j + 4 * k; };
  // outward normals: -x, +x, -y, +y, -z, +z
  return { { v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0) }, { v(1, 0, 0), v(1, 1, 0), v(1, 1, 1), v(1, 0, 1) },
    { v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1) }, { v(0, 1, 0), v(0, 1, 1), v(1, 1, 1), v(1, 1, 0) },
    { v(0, 0, 0), v(0, 1, 0), v(1, 1, 0), v(1, 0, 0) }, { v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1) } };
}

// A row of count unit cubes along x sharing their faces' points (points replaced), each cube's six
// faces as boxFaces lists them.
std::vector<CellFaces> cubeRow(PointList& points, int count)
{
  points.clear();
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i <= count; ++i)
        points.push_back(Vec3(i, j, k));
  auto v = [count](int i, int j, int k) { return i + (count + 1) * (j + 2 * k); };
  std::vector<CellFaces> cubes;
  for (int x = 0; x < count; ++x)
  {
    cubes.push_back(CellFaces{ { v(x, 0, 0), v(x, 0, 1), v(x, 1, 1), v(x, 1, 0) },
      { v(x + 1, 0, 0), v(x + 1, 1, 0), v(x + 1, 1, 1), v(x + 1, 0, 1) },
      { v(x, 0, 0), v(x + 1, 0, 0), v(x + 1, 0, 1), v(x, 0, 1) }, { v(x, 1, 0), v(x, 1, 1), v(x + 1, 1, 1), v(x + 1, 1, 0) },
      { v(x, 0, 0), v(x, 1, 0), v(x + 1, 1, 0), v(x + 1, 0, 0) }, { v(x, 0, 1), v(x + 1, 0, 1), v(x + 1, 1, 1), v(x, 1, 1) } });
  }
  return cubes;
}
}

TEST(FaceCentresAndAreas)
{
  // a unit square, an L-shaped hexagon (area 3, centroid (5/6, 5/6)) and a triangle
  const PointList points = { Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(1, 1, 0), Vec3(1, 2, 0), Vec3(0, 2, 0), Vec3(1, 0, 0),
    Vec3(0, 1, 0) };
  const FaceGeometry square = faceGeometry(points, { 0, 6, 3, 7 });
  // dyadic corners: exact in binary, 1e-15 = a few ulps of 1 (eps = 2.2e-16)
  CHECK((square.centre - Vec3(0.5, 0.5, 0)).norm() < 1e-15 && (square.area - Vec3(0, 0, 1)).norm() < 1e-15);
  const FaceGeometry hexagon = faceGeometry(points, { 0, 1, 2, 3, 4, 5 });
  std::printf("L-shape: centre (%.15g, %.15g), area %.15g\n", hexagon.centre.x(), hexagon.centre.y(), hexagon.area.z());
  // sums of 6 triangle terms of size <= 4 (and 5/6 is not dyadic): 6 x 4 x eps = 5e-15
  CHECK((hexagon.centre - Vec3(5.0 / 6, 5.0 / 6, 0)).norm() < 1e-14);
  CHECK((hexagon.area - Vec3(0, 0, 3)).norm() < 1e-14);
  const FaceGeometry triangle = faceGeometry(points, { 0, 5, 1 }); // clockwise seen from +z
  // 3 terms of size <= 4: 3 x 4 x eps = 2.7e-15
  CHECK((triangle.area - Vec3(0, 0, -2)).norm() < 1e-14);
  CHECK((triangle.centre - Vec3(2.0 / 3, 2.0 / 3, 0)).norm() < 1e-14);
}

TEST(CellCentresAndVolumes)
{
  PointList points;
  const auto box = boxFaces(points, 0, 2);
  const CellGeometry b = cellGeometry(points, box);
  // 6 pyramids of 4 triangles each, values <= 2: 24 x 2 x eps = 1.1e-14 at worst; the corners
  // are dyadic, so nearly every step is exact
  CHECK((b.centre - Vec3(1, 0.5, 0.5)).norm() < 1e-14);
  CHECK(std::abs(b.volume - 2) < 1e-14);
  // a tetrahedron: centroid = mean of the corners, volume 1/6
  const PointList tet = { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1) };
  const CellGeometry t = cellGeometry(tet, { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } });
  // values <= 1 over 4 faces of 3 triangles; 1e-15 = 4.5 ulps of 1
  CHECK((t.centre - Vec3(0.25, 0.25, 0.25)).norm() < 1e-15);
  CHECK(std::abs(t.volume - 1.0 / 6) < 1e-15);
}

TEST(NonOrthogonalityAndSkewness)
{
  // Two unit cubes sharing the face x = 1: orthogonal, not skewed.
  PointList points;
  const auto left = boxFaces(points, 0, 1);
  const auto right = boxFaces(points, 1, 2);
  const CellGeometry P = cellGeometry(points, left), N = cellGeometry(points, right);
  const FaceGeometry shared = faceGeometry(points, left[1]); // outward of the owner: towards the neighbour
  CHECK((shared.area - Vec3(1, 0, 0)).norm() < 1e-15); // dyadic: exact
  // acos near 1 turns a cosine k ulps below 1 into sqrt(2 k eps) rad: k = 2 gives 1.7e-6 degrees
  // (here the centres and the area are dyadic and the cosine is exactly 1)
  CHECK(std::abs(nonOrthogonality(P.centre, N.centre, shared.area)) < 2e-6);
  // |sv| is a difference of dyadic values, 0 exactly; 1e-14 = ~45 eps as for the case below
  CHECK(std::abs(skewness(P.centre, N.centre, shared, points, left[1])) < 1e-14);
  // Neighbour centre moved by h along y: d = (1, h, 0), so the angle is atan(h) and the line
  // P-N crosses the face h/2 from its centre, whose extent along y is 0.5: skewness h.
  const double h = 0.3;
  const Vec3 moved = N.centre + Vec3(0, h, 0);
  const double angle = nonOrthogonality(P.centre, moved, shared.area);
  const double skew = skewness(P.centre, moved, shared, points, left[1]);
  std::printf("non-orthogonality %.12g (atan(h) = %.12g degrees), skewness %.12g (h = %g)\n", angle, std::atan(h) * 180 / M_PI, skew, h);
  // the cosine 1/sqrt(1 + h^2) to a few ulps, times d(acos)/d(cos) = 1/sin(16.7 deg) = 3.5, times
  // 180/pi: 4.4e-14 degrees per ulp; 1e-12 degrees allows ~20 ulps
  CHECK(std::abs(angle - std::atan(h) * 180 / M_PI) < 1e-12);
  // ~20 operations on values <= 2 (one division by the face extent 0.5): 20 x 2 x 2 x eps = 1.8e-14
  CHECK(std::abs(skew - h) < 4e-14);
}

TEST(InteriorFacesAreMatchedAndOriented)
{
  // Two unit cubes in a row sharing the four points at x = 1; the owner's shared face is listed
  // inward, which the orientation corrects.
  PointList points;
  std::vector<CellFaces> nested = cubeRow(points, 2);
  auto v = [](int i, int j, int k) { return i + 3 * j + 6 * k; };
  std::reverse(nested[0][1].begin(), nested[0][1].end());
  const MeshFaces mesh = meshFaces(CellFaceList(nested));
  const InteriorFaces& faces = mesh.interior;
  CHECK(faces.size() == 1);
  CHECK(faces[0].owner == 0 && faces[0].neighbour == 1 && faces[0].face == 1);
  CHECK(mesh.boundary.size() == 10 && mesh.boundary[0].owner == 0 && mesh.boundary[0].face == 0 && mesh.boundary[5].owner == 1);
  const std::vector<int> orientation = faceOrientation(points, mesh);
  CHECK(orientation[0] == -1);
  const FaceMeasures before = faceMeasures(points, mesh, orientation);
  CHECK(before.nonOrthogonality[0] < 2e-6 && before.skewness[0] < 1e-14); // as in NonOrthogonalityAndSkewness
  // the face pyramids: the owner lists its shared face inward, which checkMesh reports too (an
  // incorrectly oriented face), so it counts as inverted; the neighbour is a sound cube
  CHECK(before.inverted == std::vector<unsigned char>({ 1, 0 }) && before.invertedCells == 1);
  // Fold the neighbour over the owner (its far face to x = -1): its centre is now on the
  // owner's side, so the face, kept in its original orientation, is above 90 degrees.
  PointList folded = points;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      folded[v(2, j, k)].x() = -1;
  const FaceMeasures after = faceMeasures(folded, mesh, orientation);
  std::printf("folded neighbour: non-orthogonality %.6g degrees\n", after.nonOrthogonality[0]);
  CHECK(after.nonOrthogonality[0] > 90); // the definition of a folded face: d . S < 0
  // the folded neighbour is inside out: its moved face's pyramid has negative volume
  CHECK(after.inverted[1] == 1 && after.invertedCells == 2);
  // a face shared by three cells is not a valid mesh
  nested.push_back(CellFaces{ nested[1][0] });
  CHECK_THROWS(interiorFaces(CellFaceList(nested)), std::invalid_argument);
  // Degenerate faces (a collapsed cell's) repeat points: faces of the same points and point sum
  // but other multiplicities are not one face; the same points listed in reverse are.
  const std::vector<int> repeated = { 2, 2, 2, 1, 3 }, other = { 2, 1, 1, 3, 3 };
  CHECK(interiorFaces(CellFaceList(std::vector<CellFaces>{ { repeated }, { other } })).empty());
  const std::vector<int> reversed(repeated.rbegin(), repeated.rend());
  const InteriorFaces degenerate = interiorFaces(CellFaceList(std::vector<CellFaces>{ { repeated }, { reversed } }));
  CHECK(degenerate.size() == 1 && degenerate[0].owner == 0 && degenerate[0].neighbour == 1);
}

TEST(BoundaryFaceSkewness)
{
  // A unit cube sheared along x by s per unit of z (a parallelepiped): its centre is (0.5 + s/2,
  // 0.5, 0.5), and OpenFOAM's boundary skewness of its bottom face (centre (0.5, 0.5, 0), normal
  // -z) is the tangential offset |sv| = s/2 over the face's extent along x, 0.5 (more than
  // 0.4 |d| = 0.2): s, whatever the face's orientation. Its side face x = s z (normal
  // (1, 0, -s) / sqrt(1 + s^2)) has Cpf = (-1/2, 0, 0), whose part in the face's plane is
  // s / (2 sqrt(1 + s^2)) long, over the face's extent sqrt(1 + s^2) / 2 that way: s / (1 + s^2).
  const double s = 0.3;
  PointList points;
  std::vector<CellFaces> cube = cubeRow(points, 1);
  for (Vec3& p : points)
    p.x() += s * p.z();
  const CellGeometry cell = cellGeometry(points, cube[0]);
  // dyadic but for s: ~30 operations of size <= 2: 1e-14
  CHECK((cell.centre - Vec3(0.5 + s / 2, 0.5, 0.5)).norm() < 1e-14);
  const FaceGeometry bottom = faceGeometry(points, cube[0][4]);
  const double skew = boundarySkewness(cell.centre, bottom, points, cube[0][4].data(), 4);
  std::vector<int> reversed(cube[0][4].rbegin(), cube[0][4].rend());
  const FaceGeometry flipped = faceGeometry(points, reversed);
  std::printf("sheared cube: bottom face's skewness %.15g (s = %g)\n", skew, s);
  CHECK(std::abs(skew - s) < 1e-13);
  CHECK(std::abs(boundarySkewness(cell.centre, flipped, points, reversed.data(), 4) - skew) < 1e-15);
  CHECK(std::abs(boundarySkewness(cell.centre, faceGeometry(points, cube[0][0]), points, cube[0][0].data(), 4) - s / (1 + s * s)) < 1e-14);
  // a thin cell (height 0.1) offset by 0.01 along y: 0.4 |d| = 0.02 < the extent 0.5, so 0.01 / 2 / 0.5
  const FaceGeometry thin{ Vec3(0.5, 0.5, 0), Vec3(0, 0, -1) };
  CHECK(std::abs(boundarySkewness(Vec3(0.5, 0.51, 0.05), thin, points, cube[0][4].data(), 4) - 0.02) < 1e-14);
  // the mesh: one cell, six boundary faces, the largest skewness the bottom's (and the top's)
  const MeshFaces mesh = meshFaces(CellFaceList(cube));
  CHECK(mesh.interior.empty() && mesh.boundary.size() == 6);
  const FaceMeasures m = faceMeasures(points, mesh, faceOrientation(points, mesh));
  CHECK(m.boundarySkewness.size() == 6 && std::abs(m.maxSkewness - skew) < 1e-15 && m.maxNonOrthogonality == 0);
  // two copies of the cube side by side whose points were not merged (two pieces of one mesh):
  // the faces where they touch have the same position keys, whatever their points' order, and
  // left out they are on no boundary
  PointList two = points;
  std::vector<CellFaces> cells = cube;
  for (const Vec3& p : points)
    two.push_back(p + Vec3(1, 0, 0));
  CellFaces right = cube[0];
  for (auto& face : right)
    for (int& i : face)
      i += static_cast<int>(points.size());
  std::rotate(right[0].begin(), right[0].begin() + 1, right[0].end());
  cells.push_back(right);
  MeshFaces pieces = meshFaces(CellFaceList(cells));
  CHECK(pieces.interior.empty() && pieces.boundary.size() == 12);
  const std::vector<std::uint64_t> keys = boundaryKeys(two, pieces.cells, pieces.boundary);
  CHECK(keys[1] == keys[6] && repeatedKeys(keys) == std::vector<std::uint64_t>{ keys[1] }); // the left's +x, the right's -x face
  CHECK(leaveOutFaces(pieces.boundary, keys, repeatedKeys(keys)) == 2 && pieces.boundary.size() == 10);
  CHECK(std::none_of(pieces.boundary.begin(), pieces.boundary.end(), [](const BoundaryFace& f) { return f.face == 1 || f.face == 6; }));
}

TEST(OwnerNeighbourFacesAreOpenFOAMs)
{
  // A row of three unit cubes in OpenFOAM's form: the two faces between them first (normal +x,
  // out of the owner), then each cube's boundary faces; its cells' faces and interior faces must
  // be what matching the cubes' faces finds, and measure the same.
  PointList points;
  const std::vector<CellFaces> cube = cubeRow(points, 3);
  std::vector<int> start = { 0 }, facePoints, owner, neighbour;
  auto addFace = [&](const std::vector<int>& face, int o) {
    facePoints.insert(facePoints.end(), face.begin(), face.end());
    start.push_back(static_cast<int>(facePoints.size()));
    owner.push_back(o);
  };
  for (int x = 0; x < 2; ++x)
  {
    addFace(cube[x][1], x); // the +x face, out of cube x into cube x + 1
    neighbour.push_back(x + 1);
  }
  for (int x = 0; x < 3; ++x)
    for (int f : { 0, 1, 2, 3, 4, 5 })
      if ((f != 0 || x == 0) && (f != 1 || x == 2))
        addFace(cube[x][f], x);
  const int pointCount = static_cast<int>(points.size());
  const MeshFaces mesh = ownerNeighbourFaces(start, facePoints, owner, neighbour, pointCount);
  CHECK(mesh.cells.cells() == 3 && mesh.cells.faces() == 18 && mesh.interior.size() == 2);
  for (int x = 0; x < 2; ++x)
  {
    const InteriorFace& f = mesh.interior[x];
    CHECK(f.owner == x && f.neighbour == x + 1);
    // the owner's copy is the face as listed; the neighbour lists it reversed, out of itself
    const std::vector<int> shared = cube[x][1];
    CHECK(std::equal(shared.begin(), shared.end(), mesh.cells.face(f.face)));
    CHECK(faceGeometry(points, mesh.cells.face(f.face), 4).area.isApprox(Vec3(1, 0, 0)));
    const long copy = mesh.cells.firstFace(x + 1); // face 0 of cube x + 1 is the shared one (lowest number)
    CHECK(f.neighbourFace == copy);
    CHECK(faceGeometry(points, mesh.cells.face(copy), 4).area.isApprox(Vec3(-1, 0, 0)));
  }
  // every cell's faces point out of it: no negative pyramid, orientation +1, as matched
  const MeshFaces matchedMesh = meshFaces(CellFaceList(cube));
  const InteriorFaces& matched = matchedMesh.interior;
  CHECK(mesh.boundary.size() == 14 && matchedMesh.boundary.size() == 14);
  CHECK(matched.size() == 2 && matched[0].owner == 0 && matched[1].owner == 1);
  CHECK(matched[0].face == 1 && matched[0].neighbourFace == 6 && matched[1].face == 7 && matched[1].neighbourFace == 12);
  // a sheared, non-dyadic point set: both forms sum the same face terms in another order, so
  // they agree to round-off (a few dozen operations of size <= 4: 1e-13 relative)
  PointList sheared = points;
  for (Vec3& p : sheared)
    p += Vec3(0.1 * p.y() + 0.03 * p.z() * p.x(), 0.07 * p.x() * p.z(), 0.01 * p.x() * p.y());
  const FaceMeasures own = faceMeasures(sheared, mesh, faceOrientation(sheared, mesh));
  const FaceMeasures byPoints = faceMeasures(sheared, matchedMesh, faceOrientation(sheared, matchedMesh));
  CHECK(faceOrientation(sheared, mesh) == std::vector<int>({ 1, 1 }));
  CHECK(own.invertedCells == 0 && byPoints.invertedCells == 0);
  std::printf("sheared row: non-orthogonality %.17g and %.17g, skewness %.17g and %.17g\n", own.maxNonOrthogonality,
    byPoints.maxNonOrthogonality, own.maxSkewness, byPoints.maxSkewness);
  CHECK(own.maxNonOrthogonality > 1 && std::abs(own.maxNonOrthogonality - byPoints.maxNonOrthogonality) <= 1e-13 * own.maxNonOrthogonality);
  CHECK(own.maxSkewness > 1e-3 && std::abs(own.maxSkewness - byPoints.maxSkewness) <= 1e-13 * own.maxSkewness);

  // bad input: each an invalid_argument, never an out-of-range access
  CHECK_THROWS(ownerNeighbourFaces(start, facePoints, std::vector<int>(owner.begin() + 1, owner.end()), neighbour, pointCount),
    std::invalid_argument); // fewer owners than faces
  CHECK_THROWS(ownerNeighbourFaces(start, facePoints, owner, neighbour, pointCount - 1), std::invalid_argument); // a point beyond
  std::vector<int> wrong = owner;
  wrong[0] = -1;
  CHECK_THROWS(ownerNeighbourFaces(start, facePoints, wrong, neighbour, pointCount), std::invalid_argument);
  CHECK_THROWS(ownerNeighbourFaces(start, facePoints, owner, std::vector<int>{ 0, 2 }, pointCount), std::invalid_argument); // owner = neighbour
  wrong = owner;
  std::replace(wrong.begin(), wrong.end(), 1, 3); // cell 1 loses its boundary faces, cube 2 its own
  CHECK_THROWS(ownerNeighbourFaces(start, facePoints, wrong, std::vector<int>{ 4, 2 }, pointCount), std::invalid_argument);
  std::vector<int> unordered = start;
  std::swap(unordered[1], unordered[2]);
  CHECK_THROWS(ownerNeighbourFaces(unordered, facePoints, owner, neighbour, pointCount), std::invalid_argument);
}

TEST_MAIN
