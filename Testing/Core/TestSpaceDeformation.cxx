// Section 5, eq. 12-14: the normal matrices and invariants of the solve.
#include "Basis/MLSBasis.h"
#include "Basis/RadialBasis.h"
#include "Basis/ResidualBlend.h"
#include "Solver/SpaceDeformation.h"
#include "Basis/SubspaceOperators.h"
#include "TestGeometry.h"
#include "../TestHarness.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

using namespace mlsdeform;

namespace
{
const double Epsilon = std::numeric_limits<double>::epsilon(); // 2.2e-16

struct Scene
{
  SamplingDomain box = testgeometry::tetrahedralBox(6, Vec3(3, 1, 1));
  Samples samples;
  std::vector<DirichletRegion> regions; // 0: handle x = 3, 1: fixed x = 0
  Scene()
  {
    SamplingParameters p;
    p.numberOfSurfaceSamples = 200;
    p.numberOfVolumeSamples = 100;
    p.lloydIterations = 5;
    samples = sampleDomain(box, p);
    regions.resize(2);
    for (const Vec3& x : box.points)
    {
      if (x.x() > 3 - 1e-9)
        regions[0].positions.push_back(x);
      if (x.x() < 1e-9)
        regions[1].positions.push_back(x);
    }
  }
  std::vector<PointDisplacements> uniform(const Vec3& handle, const Vec3& fixed) const
  {
    std::vector<PointDisplacements> d(2);
    d[0] = handle.transpose().replicate(regions[0].positions.size(), 1);
    d[1] = fixed.transpose().replicate(regions[1].positions.size(), 1);
    return d;
  }
};

Displacements evaluate(const SpaceDeformation& model, const Displacements& w, const PointList& x)
{
  return subspaceMatrix(model.basis(), x) * w;
}
}

TEST(GramMatricesOfDenseAndSparseBlocks)
{
  // A has full rows (multiplied by the BLAS) and rows with two entries (sparse products); the
  // accumulated Gram matrix of three row ranges is A^T W A.
  const long rows = 300, k = 40;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(rows, k);
  for (long i = 0; i < rows; ++i)
    for (long j = 0; j < k; ++j)
      if (i < 120 || j == i % k || j == (7 * i) % k)
        dense(i, j) = uniform(random);
  const SparseRowMatrix A = dense.sparseView();
  Eigen::VectorXd weight(rows);
  for (long i = 0; i < rows; ++i)
    weight[i] = 1 + uniform(random);
  const Eigen::MatrixXd expected = dense.transpose() * weight.asDiagonal() * dense;
  GramAccumulator gram(k);
  for (const auto& [begin, end] : { std::pair<long, long>(0, 120), std::pair<long, long>(120, 200), std::pair<long, long>(200, 300) })
    gram.add(A, begin, end, weight.segment(begin, end - begin));
  // Round-off: each entry sums at most 300 products, to 300 eps x the sum of their magnitudes
  // (|A|^T W |A|), in the accumulator and in the reference alike.
  const Eigen::MatrixXd magnitude = dense.cwiseAbs().transpose() * weight.asDiagonal() * dense.cwiseAbs();
  const double roundOff = 2 * rows * Epsilon * magnitude.norm();
  std::printf("round-off bound %.2e, error %.2e\n", roundOff, (Eigen::MatrixXd(gram.sum()) - expected).norm());
  CHECK((Eigen::MatrixXd(gram.sum()) - expected).norm() <= roundOff);
  CHECK((Eigen::MatrixXd(weightedGram(A, 0, 120, weight.head(120))) - dense.topRows(120).transpose() * weight.head(120).asDiagonal() * dense.topRows(120)).norm() <= roundOff);
  // The same sparse rows with their entries stored in decreasing column order (rows not made by
  // Phi's assembly need not be increasing).
  SparseRowMatrix reversed = A.bottomRows(180);
  for (long i = 0; i < reversed.rows(); ++i)
  {
    const int begin = reversed.outerIndexPtr()[i], end = reversed.outerIndexPtr()[i + 1];
    std::reverse(reversed.innerIndexPtr() + begin, reversed.innerIndexPtr() + end);
    std::reverse(reversed.valuePtr() + begin, reversed.valuePtr() + end);
  }
  const Eigen::MatrixXd bottom = dense.bottomRows(180);
  CHECK((Eigen::MatrixXd(weightedGram(reversed, 0, 180, weight.tail(180))) - bottom.transpose() * weight.tail(180).asDiagonal() * bottom).norm() <= roundOff);
}

TEST(VolumetricNormalsAreGramMatricesOfTheDerivativeRows)
{
  // eq. 12, 13: G^T G and L^T L from the derivatives at the integration points, for a sparse
  // (MLS) and a dense (biharmonic) basis
  const Scene scene;
  const PointList& q = scene.samples.integrationPoints;
  const std::vector<double>& V = scene.samples.volume;
  const MLSBasis mls(scene.samples.centers, scene.samples.supportRadius);
  const RadialBasis biharmonic(RadialKernel::Biharmonic, scene.samples.centers, scene.samples.supportRadius);
  for (const ShapeFunctions* basis : { static_cast<const ShapeFunctions*>(&mls), static_cast<const ShapeFunctions*>(&biharmonic) })
  {
    const long k = static_cast<long>(basis->size()), n = static_cast<long>(q.size());
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(3 * n, k), L = Eigen::MatrixXd::Zero(n, k);
    ShapeFunctionValues phi;
    for (long i = 0; i < n; ++i)
    {
      basis->evaluate(q[i], phi, true);
      for (std::size_t a = 0; a < phi.index.size(); ++a)
      {
        G.block(3 * i, phi.index[a], 3, 1) = 0.5 * std::sqrt(V[i]) * phi.gradient[a];
        L(i, phi.index[a]) = 2.0 * std::sqrt(V[i]) * phi.laplacian[a];
      }
    }
    const EnergyNormals normals = volumetricEnergyNormals(*basis, q, V, 0.5, 2.0);
    const Eigen::MatrixXd GG = G.transpose() * G, LL = L.transpose() * L;
    // Round-off as in GramMatricesOfDenseAndSparseBlocks: sums over the 3n (n) rows, to that many
    // eps x |G|^T |G| (|L|^T |L|), in both computations.
    const double stretchRoundOff = 2 * 3 * n * Epsilon * (G.cwiseAbs().transpose() * G.cwiseAbs()).norm();
    const double bendRoundOff = 2 * n * Epsilon * (L.cwiseAbs().transpose() * L.cwiseAbs()).norm();
    std::printf("stretch: error %.2e (round-off bound %.2e), bend: error %.2e (%.2e)\n", (Eigen::MatrixXd(normals.stretch) - GG).norm(),
      stretchRoundOff, (Eigen::MatrixXd(normals.bend) - LL).norm(), bendRoundOff);
    CHECK(normals.points == n);
    CHECK((Eigen::MatrixXd(normals.stretch) - GG).norm() <= stretchRoundOff);
    CHECK((Eigen::MatrixXd(normals.bend) - LL).norm() <= bendRoundOff);
  }
}

TEST(PhiInRowBlocksIsTheEvaluatedShapeFunctions)
{
  // Phi at 10,000 positions (3 row blocks) and 5 far outside: every row holds the shape functions
  // as evaluated, rounded to PhiValue (the same operations, so exactly; within 2^-24 relative of
  // the double values), the double matrix holds the same values, and d = Phi w over a row range
  // that crosses blocks is the same in either form (each row summed in its order by one thread).
  const Scene scene;
  const MLSBasis basis(scene.samples.centers, scene.samples.supportRadius);
  PointList x = testgeometry::randomPoints(10000, Vec3(0, 0, 0), Vec3(3, 1, 1), 3);
  for (int i = 0; i < 5; ++i)
    x.insert(x.begin() + 4096 * i / 2, Vec3(100, 100, 100));
  std::vector<int> outside;
  const RowBlocks blocks = subspaceBlocks(basis, x, &outside);
  CHECK(blocks.blocks.size() == 3 && blocks.rows() == static_cast<long>(x.size()) && blocks.columns == static_cast<long>(basis.size()));
  CHECK(outside == std::vector<int>({ 0, 2048, 4096, 6144, 8192 }));
  const SparseRowMatrix Phi = subspaceMatrix(basis, x);
  CHECK(Phi.rows() == blocks.rows() && Phi.cols() == blocks.columns);
  ShapeFunctionValues phi;
  bool rowsExact = true;
  double rounding = 0; // the largest relative change of an entry by its rounding
  for (long i = 0; i < Phi.rows(); ++i)
  {
    basis.evaluate(x[i], phi, false);
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(Phi.cols());
    for (std::size_t a = 0; a < phi.index.size(); ++a)
    {
      expected[phi.index[a]] = static_cast<PhiValue>(phi.value[a]);
      rounding = std::max(rounding, std::abs(expected[phi.index[a]] - phi.value[a]) / std::abs(phi.value[a]));
    }
    const PhiRowSpan row = rowOf(blocks, i);
    Eigen::VectorXd fromBlock = Eigen::VectorXd::Zero(Phi.cols());
    for (long a = 0; a < row.size; ++a)
      fromBlock[row.column(a)] = row.value[a];
    rowsExact = rowsExact && Eigen::VectorXd(Phi.row(i).transpose()) == expected && fromBlock == expected &&
      Phi.row(i).nonZeros() == static_cast<long>(phi.index.size()) && row.size == Phi.row(i).nonZeros();
  }
  CHECK(rowsExact);
  CHECK(rounding <= std::ldexp(1.0, -24));
  const Displacements w = Displacements::Random(Phi.cols(), 3);
  const long begin = 3000, end = 9000;
  PointDisplacements fromBlocks(end - begin, 3), fromMatrix(end - begin, 3);
  multiplyRows(blocks, w, begin, end, fromBlocks.data());
  multiplyRows(Phi, w, begin, end, fromMatrix.data());
  CHECK(fromBlocks == fromMatrix);
  // Eigen's product, summed in its own order: a sum of n terms rounds by at most n eps times the
  // sum of their magnitudes, (|Phi| |w|)_i, in each of the two sums
  long longest = 0;
  for (long i = 0; i < Phi.rows(); ++i)
    longest = std::max(longest, static_cast<long>(Phi.row(i).nonZeros()));
  const double roundOff = 2 * longest * Epsilon * PointDisplacements(Phi.cwiseAbs() * w.cwiseAbs()).maxCoeff();
  CHECK((fromMatrix - PointDisplacements((Phi * w).middleRows(begin, end - begin))).cwiseAbs().maxCoeff() <= roundOff);
}

// Shape functions of many columns scattered over [0, k): position (i, 0, 0) meets `width` of them,
// a pseudo-random spread, with values that tell the entries apart.
class ScatteredShapeFunctions : public ShapeFunctions
{
public:
  ScatteredShapeFunctions(long k, long width)
    : K(k)
    , Width(width)
  {
  }
  void evaluate(const Vec3& x, ShapeFunctionValues& out, bool) const override
  {
    const long i = std::lround(x.x());
    out.index.clear();
    out.value.clear();
    for (long j = 0; j < Width; ++j)
      out.index.push_back(static_cast<int>(((i * Width + j) * 7919) % K));
    std::sort(out.index.begin(), out.index.end());
    out.index.erase(std::unique(out.index.begin(), out.index.end()), out.index.end());
    for (int column : out.index)
      out.value.push_back(1.0 / (1.0 + column + i));
  }
  std::size_t size() const override { return static_cast<std::size_t>(K); }

private:
  long K, Width;
};

TEST(PhiRowsSplitWhereABlockMeetsMoreThan65536Columns)
{
  // 4096 positions meeting 40 of 200,000 columns each use more columns than one table's 65536
  // places: the block holds several parts, and every row still reads back as evaluated. A row
  // alone in more supports than that is refused with a clear error.
  const ScatteredShapeFunctions wide(200000, 40);
  PointList x;
  for (int i = 0; i < 5000; ++i)
    x.emplace_back(i, 0, 0);
  const RowBlocks blocks = subspaceBlocks(wide, x);
  CHECK(blocks.blocks.size() == 2 && blocks.blocks[0].parts.size() >= 2 && blocks.rows() == 5000);
  bool same = true;
  ShapeFunctionValues phi;
  for (long i = 0; same && i < 5000; ++i)
  {
    wide.evaluate(x[i], phi, false);
    const PhiRowSpan row = rowOf(blocks, i);
    same = row.size == static_cast<long>(phi.index.size());
    for (long a = 0; same && a < row.size; ++a)
      same = row.column(a) == phi.index[a] && row.value[a] == static_cast<PhiValue>(phi.value[a]);
  }
  CHECK(same);
  for (const PhiBlock& block : blocks.blocks)
    for (const PhiRows& part : block.parts)
      CHECK(part.columns.size() <= 65536);
  const ScatteredShapeFunctions wider(200000, 70000);
  bool refused = false;
  try
  {
    subspaceBlocks(wider, PointList{ Vec3(1, 0, 0) });
  }
  catch (const InvalidInputException& e)
  {
    refused = std::string(e.what()).find("65536") != std::string::npos;
  }
  CHECK(refused);
}

TEST(KnownRowsAreViewedAsTheyWouldBeEvaluated)
{
  // Phi at region positions viewed in the rows of the points they coincide with (a patch of the
  // mesh) is the matrix evaluated at them, bit for bit; positions at no point (or outside every
  // support) are evaluated. A position matches the first point at exactly its coordinates, -0 as
  // +0. The views survive a move of the gathered rows.
  const Scene scene;
  const MLSBasis basis(scene.samples.centers, scene.samples.supportRadius);
  PointList x = testgeometry::randomPoints(10000, Vec3(0, 0, 0), Vec3(3, 1, 1), 4);
  x[100] = Vec3(0, 0.5, 0.5);
  x[7000] = x[5]; // a point stored twice (a patch's point and the volume's)
  const RowBlocks blocks = subspaceBlocks(basis, x);
  PointList positions = { x[9000], x[5], Vec3(-0.0, 0.5, 0.5), Vec3(1.5, 0.5, 0.5), Vec3(100, 100, 100), x[4096] };
  positions.back().x() = std::nextafter(positions.back().x(), 10.0); // one ulp from a point: not it
  const std::vector<long> among = positionsAmong(x, positions);
  CHECK(among == std::vector<long>({ 9000, 5, 100, -1, -1, -1 }));
  PointList twice = positions; // a position listed twice (two regions sharing a point) finds the same point
  twice.push_back(x[5]);
  CHECK(positionsAmong(x, twice) == std::vector<long>({ 9000, 5, 100, -1, -1, -1, 5 }));
  std::vector<int> outside, outsideGathered;
  const SparseRowMatrix evaluated = subspaceMatrix(basis, positions, &outside);
  GatheredRows moved = gatherRows(basis, positions, { &blocks, among }, &outsideGathered);
  const GatheredRows gathered = std::move(moved);
  CHECK(outside == std::vector<int>({ 4 }) && outsideGathered == outside);
  CHECK(gathered.rows() == evaluated.rows() && gathered.cols() == evaluated.cols());
  CHECK(gathered.row(0).place == rowOf(blocks, 9000).place && gathered.row(1).value == rowOf(blocks, 5).value); // views, not copies
  bool same = gathered.rows() == evaluated.rows();
  for (long i = 0; same && i < evaluated.rows(); ++i)
  {
    const PhiRowSpan a = rowOf(gathered, i);
    const RowSpan<double> b = rowOf(evaluated, i);
    same = a.size == b.size && std::equal(a.value, a.value + a.size, b.value, [](PhiValue f, double v) { return f == v; });
    for (long e = 0; same && e < a.size; ++e)
      same = a.column(e) == b.column(e);
  }
  CHECK(same);
}

TEST(TransposedProductsOfSeveralFunctionsAreEachAlone)
{
  // Phi^T g_f for several functions at once given by their non-zero rows (DeformationSession's
  // reverse mode): the dense ones in one pass, the sparse ones alone over their rows; each the
  // bits of its own dense product, with the rows in storage order or not
  const Scene scene;
  const MLSBasis basis(scene.samples.centers, scene.samples.supportRadius);
  const PointList x = testgeometry::randomPoints(20000, Vec3(0, 0, 0), Vec3(3, 1, 1), 5);
  const RowBlocks blocks = subspaceBlocks(basis, x);
  std::vector<long> all(x.size());
  std::iota(all.begin(), all.end(), 0L);
  const GatheredRows rows = gatherRows(basis, x, { &blocks, all });
  std::vector<PointDisplacements> g;
  for (int f = 0; f < 5; ++f)
  {
    g.push_back(PointDisplacements::Random(rows.rows(), 3));
  }
  g[1].bottomRows(rows.rows() / 2).setZero();      // dense enough: in the pass with the others
  g[3].bottomRows(rows.rows() - 100).setZero();    // on a few rows: alone
  g[3].row(40).setZero();
  g[4].setZero();                                  // no row
  SparseGradients nonZero; // each function's non-zero rows
  for (const PointDisplacements& gf : g)
  {
    for (long i = 0; i < gf.rows(); ++i)
    {
      if (!(gf.row(i).array() == 0).all())
      {
        nonZero.rows.push_back(i);
        nonZero.values.insert(nonZero.values.end(), { gf(i, 0), gf(i, 1), gf(i, 2) });
      }
    }
    nonZero.starts.push_back(static_cast<long>(nonZero.rows.size()));
  }
  CHECK(nonZero.starts[4] - nonZero.starts[3] == 99);
  const std::vector<PointDisplacements> each = multiplyTransposedEach(rows, nonZero);
  CHECK(each.size() == g.size());
  for (std::size_t f = 0; f < g.size(); ++f)
  {
    const PointDisplacements alone = multiplyTransposed(rows, 0, rows.rows(), g[f], true);
    CHECK(each[f].rows() == rows.cols() && each[f].cols() == 3 && (each[f].array() == alone.array()).all());
  }
  CHECK(each[0].norm() > 0 && each[4].norm() == 0);
  // rows gathered without their storage order (a gradient's) are read in turn: the same products
  const GatheredRows inTurn = gatherRows(basis, x, { &blocks, all }, nullptr, {}, false);
  CHECK(inTurn.order(0, inTurn.rows()) == nullptr && rows.order(0, rows.rows()) != nullptr);
  const Displacements w = Displacements::Random(rows.cols(), 3);
  PointDisplacements sorted(rows.rows(), 3), turn(rows.rows(), 3);
  multiplyRows(rows, w, 0, rows.rows(), sorted.data());
  multiplyRows(inTurn, w, 0, inTurn.rows(), turn.data());
  CHECK((sorted.array() == turn.array()).all() && (multiplyTransposed(inTurn, 0, inTurn.rows(), g[0]).array() == each[0].array()).all());
}

TEST(ResidualBlendInterpolatesTheSitesAndFades)
{
  // psi_j(x_j) = 1 exactly (a point at a site takes its own residual, -0 as +0); between sites a
  // convex combination of the K nearest; nothing beyond R of every site; the sites must be distinct
  std::vector<long> siteOf;
  const PointList sites = uniqueSites(testgeometry::randomPoints(500, Vec3(0, 0, 0), Vec3(1, 1, 1), 9), siteOf);
  const ResidualBlend blend(sites, 0.5);
  ShapeFunctionValues psi;
  blend.evaluate(sites[17], psi, false);
  CHECK(psi.index == std::vector<int>({ 17 }) && psi.value == std::vector<double>({ 1.0 }));
  PointList signedZero = { Vec3(0.0, 0.5, 0.5), Vec3(0.5, 0.5, 0.5) };
  const ResidualBlend onAxis(signedZero, 0.5);
  onAxis.evaluate(Vec3(-0.0, 0.5, 0.5), psi, false);
  CHECK(psi.index == std::vector<int>({ 0 }) && psi.value == std::vector<double>({ 1.0 }));
  blend.evaluate(Vec3(0.51, 0.49, 0.5), psi, false);
  double sum = 0;
  for (double v : psi.value)
    sum += v;
  // the weights sum to beta of the sites' distances over R: below 1, and above beta(0.4) = 0.337 as
  // the 8 nearest of 500 points in the unit cube lie well within 0.2 of x
  CHECK(psi.index.size() > 1 && psi.index.size() <= 8 && sum <= 1 + 1e-12 && sum > 0.33);
  blend.evaluate(Vec3(5, 5, 5), psi, false);
  CHECK(psi.empty());
  CHECK_THROWS(ResidualBlend({ Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 0) }, 0.5), InvalidInputException);
}

TEST(CommonTranslationMovesEveryPointByIt)
{
  Scene scene;
  for (const EnergyWeights& weights : { EnergyWeights{ 1, 0, 1000 }, EnergyWeights{ 0, 1, 1000 }, EnergyWeights{ 1, 0.6, 100 } })
  {
    SpaceDeformation model(scene.samples);
    model.setRegions(scene.regions);
    model.factorize(weights);
    const Vec3 t(0.3, -0.2, 0.5);
    const Displacements w = model.solve(scene.uniform(t, t)).w;
    const Displacements d = evaluate(model, w, scene.box.points);
    const double error = (d.rowwise() - t.transpose()).rowwise().norm().maxCoeff() / t.norm();
    // Exact in exact arithmetic with exact shape functions (MLS reproduces constants, on which
    // every energy vanishes), so: the solve's round-off, k eps cond for k coefficients, with
    // CHOLMOD's estimate 1 / rcond of the condition (the values are partitions of unity of the
    // coefficients' errors); and Phi's entries rounded to PhiValue, each by at most 2^-24 of its
    // size, a relative change of a row by 2^-24 sum_j |Phi_ij|, which the least-squares solution
    // amplifies by at most the condition (first order).
    const SparseRowMatrix Phi = subspaceMatrix(model.basis(), scene.box.points);
    const double rowSum = Eigen::VectorXd(Phi.cwiseAbs() * Eigen::VectorXd::Ones(Phi.cols())).maxCoeff();
    const double roundOff =
      (static_cast<double>(model.basis().size()) * Epsilon + std::ldexp(1.0, -24) * rowSum) / model.reciprocalCondition();
    std::printf("gamma_s %g gamma_b %g: max relative error %g, rcond %g, round-off bound %g\n", weights.stretch, weights.bend, error,
      model.reciprocalCondition(), roundOff);
    CHECK(error <= roundOff);
  }
}

TEST(OnlyFixedRegionsMoveNothing)
{
  Scene scene;
  SpaceDeformation model(scene.samples);
  model.setRegions(scene.regions);
  model.factorize(EnergyWeights{});
  const Displacements w = model.solve(scene.uniform(Vec3::Zero(), Vec3::Zero())).w;
  CHECK(evaluate(model, w, scene.box.points).cwiseAbs().maxCoeff() == 0.0);
}

TEST(HandleAndFixedTargetsAreMet)
{
  Scene scene;
  SpaceDeformation model(scene.samples);
  model.setRegions(scene.regions);
  model.factorize(EnergyWeights{ 0, 1, 1000 });
  const Vec3 lift(0, 0, 0.5);
  const auto prescribed = scene.uniform(lift, Vec3::Zero());
  const SpaceDeformation::Solution solution = model.solve(prescribed);
  const Displacements& w = solution.w;
  // the residuals from the quadratic forms equal those measured at the region points
  for (int r = 0; r < 2; ++r)
  {
    const Displacements d = evaluate(model, w, scene.regions[r].positions);
    const double measured = std::sqrt((d - prescribed[r]).squaredNorm() / d.rows());
    const double largest = (d - prescribed[r]).rowwise().norm().maxCoeff();
    std::printf("region %d: rms residual %g, measured %g, largest %g (of %g)\n", r, solution.rmsResidual[r], measured, largest, lift.norm());
    // The quadratic form w^T A w - 2 w^T b + |dbar|^2 is a difference of terms of size |lift|^2
    // (the middle one doubled), each a sum over k coefficients: its round-off 4 k eps |lift|^2
    // becomes sqrt(4 k eps) |lift| = 5e-7 |lift| in the root (half the digits are lost).
    CHECK_NEAR(solution.rmsResidual[r], measured, std::sqrt(4 * static_cast<double>(model.basis().size()) * Epsilon) * lift.norm());
    // The bending optimum is the linear field lift x / 3 (no Laplacian), which MLS reproduces:
    // only the stretching floor (1e-6 gamma_b against gamma_f = 1000, relative 1e-9) and round-off
    // keep the targets from being met exactly; 1e-6 of the lift is far above both and far below
    // any real miss.
    CHECK(largest <= 1e-6 * lift.norm());
  }
  // the middle moves part of the way, monotonically along the bar (the linear field: 1/4, 1/2, 3/4)
  const Displacements d = evaluate(model, w, { Vec3(0.75, 0.5, 0.5), Vec3(1.5, 0.5, 0.5), Vec3(2.25, 0.5, 0.5) });
  CHECK(0 < d(0, 2) && d(0, 2) < d(1, 2) && d(1, 2) < d(2, 2) && d(2, 2) < 0.5);
}

TEST(SingularSystemIsReported)
{
  Scene scene;
  SpaceDeformation model(scene.samples);
  model.setRegions(scene.regions);
  CHECK_THROWS(model.factorize(EnergyWeights{ 0, 0, 1000 }), SolverException);
  CHECK_THROWS(model.solve(scene.uniform(Vec3::Zero(), Vec3::Zero())), SolverException);
}

TEST(BadRegionsAreRejected)
{
  Scene scene;
  SpaceDeformation model(scene.samples);
  std::vector<DirichletRegion> regions = scene.regions;
  regions[1].positions.clear();
  CHECK_THROWS(model.setRegions(regions), InvalidInputException);
  regions[1].positions = { Vec3(100, 0, 0) };
  CHECK_THROWS(model.setRegions(regions), InvalidInputException);
  regions[1].positions = { Vec3(0, std::nan(""), 0) };
  CHECK_THROWS(model.setRegions(regions), InvalidInputException);
}

TEST_MAIN
