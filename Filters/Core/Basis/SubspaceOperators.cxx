#include "Basis/SubspaceOperators.h"

#include "Common/PositionIndex.h"
#include "Common/ZOrder.h"

#include <algorithm>
#include <atomic>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <string>

#include <omp.h>

// The BLAS's symmetric rank-k update C = alpha A^T A + beta C (Fortran interface; CHOLMOD links
// the same BLAS).
extern "C" void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
  const int* lda, const double* beta, double* c, const int* ldc, std::size_t uploLength, std::size_t transLength);

namespace mlsdeform
{
namespace
{
template <typename Scalar>
using SparseRows = Eigen::SparseMatrix<Scalar, Eigen::RowMajor>;

// A block's rows from its positions' entries, kept in the block's form. The entries of position
// i (first <= i < last) are its rowsPerPoint rows, one after the other, each rowLength[i - first]
// long, from start[i - first] in columns and values.
struct BlockEntries
{
  const std::vector<int>& columns;
  const std::vector<double>& values;
  const std::vector<long>& start;
  const std::vector<long>& rowLength;
  long first, last;
  int rowsPerPoint;
  long rows() const { return (last - first) * rowsPerPoint; }
  // the entries of row r of the block (of position first + r / rowsPerPoint)
  long begin(long r) const { return start[r / rowsPerPoint] + (r % rowsPerPoint) * rowLength[r / rowsPerPoint]; }
  long length(long r) const { return rowLength[r / rowsPerPoint]; }
};

// As a row-major sparse matrix of Scalar entries (true: any rows fit).
template <typename Scalar>
bool storeBlock(const BlockEntries& e, long columnCount, SparseRows<Scalar>& block, std::vector<int>&)
{
  long entries = 0;
  for (long r = 0; r < e.rows(); ++r)
  {
    entries += e.length(r);
  }
  block.resize(e.rows(), columnCount);
  block.resizeNonZeros(entries);
  auto* outer = block.outerIndexPtr();
  outer[0] = 0;
  for (long r = 0; r < e.rows(); ++r)
  {
    const long from = e.begin(r), length = e.length(r);
    std::copy(e.columns.begin() + from, e.columns.begin() + from + length, block.innerIndexPtr() + outer[r]);
    std::copy(e.values.begin() + from, e.values.begin() + from + length, block.valuePtr() + outer[r]);
    outer[r + 1] = static_cast<int>(outer[r] + length);
  }
  return true;
}

// As PhiRows: consecutive rows while their columns fit one table of 65536 places; false if a row
// alone has more columns. mark (scratch: one entry per column, -1 but while a part is filled)
// holds a column's place in the part.
bool storeBlock(const BlockEntries& e, long columnCount, PhiBlock& block, std::vector<int>& mark)
{
  constexpr long Places = 1L << (8 * sizeof(PhiPlace));
  if (mark.empty())
  {
    mark.assign(static_cast<std::size_t>(columnCount), -1);
  }
  std::vector<int> used;
  auto close = [&](long firstRow, long lastRow) {
    PhiRows part;
    part.start.resize(static_cast<std::size_t>(lastRow - firstRow) + 1);
    part.start[0] = 0;
    for (long r = firstRow; r < lastRow; ++r)
    {
      part.start[r - firstRow + 1] = part.start[r - firstRow] + static_cast<int>(e.length(r));
    }
    part.place.resize(static_cast<std::size_t>(part.start.back()));
    part.value.resize(part.place.size());
    for (long r = firstRow; r < lastRow; ++r)
    {
      const long from = e.begin(r);
      for (long a = 0; a < e.length(r); ++a)
      {
        part.place[part.start[r - firstRow] + a] = static_cast<PhiPlace>(mark[e.columns[from + a]]);
        part.value[part.start[r - firstRow] + a] = static_cast<PhiValue>(e.values[from + a]);
      }
    }
    for (int column : used)
    {
      mark[column] = -1;
    }
    part.columns = std::move(used);
    used = std::vector<int>();
    block.parts.push_back(std::move(part));
  };
  long firstRow = 0;
  for (long r = 0; r < e.rows(); ++r)
  {
    const long from = e.begin(r), length = e.length(r);
    long added = 0; // the row's columns new to the part
    for (long a = 0; a < length; ++a)
    {
      added += mark[e.columns[from + a]] < 0 ? 1 : 0;
    }
    if (static_cast<long>(used.size()) + added > Places)
    {
      if (r == firstRow)
      {
        return false;
      }
      close(firstRow, r);
      firstRow = r;
    }
    for (long a = 0; a < length; ++a)
    {
      if (mark[e.columns[from + a]] < 0) // a place in the order first met
      {
        mark[e.columns[from + a]] = static_cast<int>(used.size());
        used.push_back(e.columns[from + a]);
      }
    }
  }
  close(firstRow, e.rows());
  return true;
}

// Assembles a row-major sparse matrix with rowsPerPoint rows per position in row blocks of
// Chunk positions, evaluated in parallel; fill(i, values, rows) writes the rows of position i
// from its shape functions. Within a chunk the positions are taken in Z-order, Group at a time,
// so that a group shares one search for its candidate shape functions (the result does not
// depend on the grouping: each position filters the candidates with the exact support test).
template <typename Block, typename Fill>
RowBlocksOf<Block> assembleRows(const ShapeFunctions& basis, const PointList& positions, int rowsPerPoint,
  bool withDerivatives, Fill fill, std::vector<int>* outside, const Progress& progress)
{
  const long n = static_cast<long>(positions.size());
  constexpr long Chunk = 4096;
  // Positions per shared search: Phi on the 400k-point hull case took 0.61-0.64 s with 128,
  // 0.62-0.69 s with 64 and 0.67-0.76 s with 16 (1M points: 1.23-1.36 s against 1.46-1.49 s),
  // the candidates' exact test being cheaper than a search per few positions.
  constexpr std::size_t Group = 128;
  // The group's candidates narrowed to those of each Part consecutive positions, which each
  // position then tests (a third of a group's candidates hold a given position). Phi on the 400k
  // hull case, 2 threads, interleaved runs: 0.44-0.59 s without, 0.34-0.46 s with parts of 16,
  // 0.33-0.34 s with 8, 0.36-0.41 s with 4.
  constexpr long Part = 8;
  const long chunks = (n + Chunk - 1) / Chunk;
  RowBlocksOf<Block> A;
  A.rowsPerBlock = Chunk * rowsPerPoint;
  A.columns = static_cast<long>(basis.size());
  A.blocks.resize(chunks);
  std::vector<std::vector<int>> outsideOf(chunks);
  long done = 0;
  std::atomic<bool> stopped{ false }; // asked to stop: the chunks not begun are skipped
  std::atomic<bool> tooWide{ false };  // a row the block's form cannot hold
#pragma omp parallel
  {
    ShapeFunctionValues phi;
    std::vector<std::vector<double>> rows(rowsPerPoint);
    std::vector<int> columns, candidates, narrowed;
    std::vector<double> values;
    std::vector<long> start(Chunk), rowLength(Chunk); // of each position's rows in columns and values
    std::vector<int> mark;                            // storeBlock's scratch
#pragma omp for schedule(dynamic)
    for (long c = 0; c < chunks; ++c)
    {
      if (stopped)
      {
        continue;
      }
      columns.clear();
      values.clear();
      const long first = c * Chunk, last = std::min(n, first + Chunk);
      forEachNearbyGroup(positions, first, last, Group, [&](const int* begin, const int* end, const Vec3& lower, const Vec3& upper) {
        const bool shared = basis.candidatesInBox(lower, upper, candidates);
        for (const int* at = begin; at < end; ++at)
        {
          const long i = *at;
          if (shared && (at - begin) % Part == 0) // the next Part positions' own candidates
          {
            Vec3 partLower, partUpper;
            boundingBoxOf(positions, at, std::min(end, at + Part), partLower, partUpper);
            basis.narrowCandidates(partLower, partUpper, candidates, narrowed);
          }
          if (shared)
          {
            basis.evaluateAmong(positions[i], narrowed, phi, withDerivatives);
          }
          else
          {
            basis.evaluate(positions[i], phi, withDerivatives);
          }
          if (phi.empty())
          {
            outsideOf[c].push_back(static_cast<int>(i));
          }
          for (auto& row : rows)
          {
            row.resize(phi.index.size());
          }
          fill(i, phi, rows);
          start[i - first] = static_cast<long>(columns.size());
          rowLength[i - first] = static_cast<long>(phi.index.size());
          for (const auto& row : rows)
          {
            columns.insert(columns.end(), phi.index.begin(), phi.index.end());
            values.insert(values.end(), row.begin(), row.end());
          }
        }
      });
      std::sort(outsideOf[c].begin(), outsideOf[c].end());
      // the block at its exact size, in the positions' order
      if (!storeBlock(BlockEntries{ columns, values, start, rowLength, first, last, rowsPerPoint }, A.columns, A.blocks[c], mark))
      {
        tooWide = true;
      }
#pragma omp atomic
      ++done;
      if (omp_get_thread_num() == 0)
      {
        progress.report(static_cast<double>(done) / chunks);
        stopped = progress.stopping();
      }
    }
  }
  if (tooWide) // thrown after the parallel region: no exception may leave it
  {
    throw InvalidInputException("a position lies in the supports of more than 65536 shape functions: too many samples for "
                                "their support radii");
  }
  if (stopped)
  {
    throw AbortedException("cancelled");
  }
  if (outside)
  {
    for (const std::vector<int>& part : outsideOf)
    {
      outside->insert(outside->end(), part.begin(), part.end());
    }
  }
  return A;
}

// The blocks as one matrix.
template <typename Matrix>
Matrix concatenate(const RowBlocksOf<Matrix>& A)
{
  long nonZeros = 0;
  for (const Matrix& block : A.blocks)
  {
    nonZeros += block.nonZeros();
  }
  Matrix B(A.rows(), A.columns);
  B.resizeNonZeros(nonZeros);
  auto* outer = B.outerIndexPtr();
  outer[0] = 0;
  long row = 0;
  for (const Matrix& block : A.blocks)
  {
    const long offset = outer[row];
    std::copy(block.innerIndexPtr(), block.innerIndexPtr() + block.nonZeros(), B.innerIndexPtr() + offset);
    std::copy(block.valuePtr(), block.valuePtr() + block.nonZeros(), B.valuePtr() + offset);
    for (long r = 0; r < block.rows(); ++r, ++row)
    {
      outer[row + 1] = static_cast<int>(offset + block.outerIndexPtr()[r + 1]);
    }
  }
  return B;
}

// The rows of A for which keep(row) holds, in their order.
template <typename Keep>
SparseRowMatrix selectRows(const SparseRowMatrix& A, Keep keep)
{
  long rows = 0, nonZeros = 0;
  for (long row = 0; row < A.rows(); ++row)
  {
    if (keep(row))
    {
      ++rows;
      nonZeros += A.outerIndexPtr()[row + 1] - A.outerIndexPtr()[row];
    }
  }
  SparseRowMatrix B(rows, A.cols());
  B.resizeNonZeros(nonZeros);
  auto* outer = B.outerIndexPtr();
  outer[0] = 0;
  long out = 0;
  for (long row = 0; row < A.rows(); ++row)
  {
    if (keep(row))
    {
      const auto begin = A.outerIndexPtr()[row], end = A.outerIndexPtr()[row + 1];
      std::copy(A.innerIndexPtr() + begin, A.innerIndexPtr() + end, B.innerIndexPtr() + outer[out]);
      std::copy(A.valuePtr() + begin, A.valuePtr() + end, B.valuePtr() + outer[out]);
      outer[out + 1] = outer[out] + (end - begin);
      ++out;
    }
  }
  return B;
}
}

GramAccumulator::GramAccumulator(long size)
  : Size(size)
  , Sparse(size, size)
{
}

void GramAccumulator::add(const SparseRowMatrix& A, long begin, long end, const Eigen::VectorXd& rowWeight)
{
  addRows(A, begin, end, rowWeight);
}

void GramAccumulator::add(const GatheredRows& A, long begin, long end, const Eigen::VectorXd& rowWeight)
{
  addRows(A, begin, end, rowWeight);
}

template <typename Rows>
void GramAccumulator::addRows(const Rows& A, long begin, long end, const Eigen::VectorXd& rowWeight)
{
  const long rows = end - begin;
  double entries = 0;
  for (long row = begin; row < end; ++row)
  {
    entries += static_cast<double>(rowOf(A, row).size);
  }
  if (entries > 0.25 * static_cast<double>(rows) * static_cast<double>(Size))
  {
    // dense: DenseLower += B^T B with B = diag(sqrt(rowWeight)) A(begin:end, :)
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(rows, Size);
    for (long row = 0; row < rows; ++row)
    {
      const auto r = rowOf(A, begin + row);
      for (long a = 0; a < r.size; ++a)
      {
        B(row, r.column(a)) = r.value[a];
      }
    }
    B = rowWeight.cwiseSqrt().asDiagonal() * B;
    if (DenseLower.size() == 0)
    {
      DenseLower = Eigen::MatrixXd::Zero(Size, Size);
    }
    const int n = static_cast<int>(Size), k = static_cast<int>(rows);
    const double one = 1.0;
    dsyrk_("L", "T", &n, &k, &one, B.data(), &k, &one, DenseLower.data(), &n, 1, 1);
    return;
  }
  // chunks of a fixed number of rows, not one per thread: the partial sums, and so the rounding of
  // their sum, must not depend on the number of threads. A chunk's rows (nearby positions) share
  // few columns: its Gram is summed in a dense matrix over those, row by row as outer products,
  // then stored sparse (Eigen's sparse product took 0.38 s for the 66k rows of a hull region).
  constexpr long ChunkRows = 8192;
  const long chunks = std::max(1L, (rows + ChunkRows - 1) / ChunkRows);
  std::vector<SparseMatrix> parts(chunks);
#pragma omp parallel
  {
    std::vector<int> local(static_cast<std::size_t>(Size), -1); // a column's number in the chunk
    std::vector<int> used;                                      // the chunk's columns, increasing
    std::vector<std::pair<int, double>> rowEntries; // (number in the chunk, value)
    Eigen::MatrixXd G;
    std::vector<Eigen::Triplet<double>> entries;
#pragma omp for schedule(dynamic, 1)
    for (long c = 0; c < chunks; ++c)
    {
      const long first = c * ChunkRows, last = std::min(rows, first + ChunkRows);
      used.clear();
      for (long row = first; row < last; ++row)
      {
        const auto r = rowOf(A, begin + row);
        for (long e = 0; e < r.size; ++e)
        {
          if (local[r.column(e)] < 0)
          {
            local[r.column(e)] = 0;
            used.push_back(r.column(e));
          }
        }
      }
      std::sort(used.begin(), used.end());
      const long m = static_cast<long>(used.size());
      for (long i = 0; i < m; ++i)
      {
        local[used[i]] = static_cast<int>(i);
      }
      G.setZero(m, m);
      for (long row = first; row < last; ++row)
      {
        const auto r = rowOf(A, begin + row);
        const long n = r.size;
        rowEntries.resize(n);
        for (long a = 0; a < n; ++a)
        {
          rowEntries[a] = { local[r.column(a)], r.value[a] };
        }
        if (!std::is_sorted(rowEntries.begin(), rowEntries.end())) // Phi's rows are; others need not be
        {
          std::sort(rowEntries.begin(), rowEntries.end());
        }
        for (long b = 0; b < n; ++b)
        {
          // the lower triangle: entry a >= b is in row >= column
          const double weighted = rowWeight[row] * rowEntries[b].second;
          double* column = G.col(rowEntries[b].first).data();
          for (long a = b; a < n; ++a)
          {
            column[rowEntries[a].first] += weighted * rowEntries[a].second;
          }
        }
      }
      entries.clear();
      for (long j = 0; j < m; ++j)
      {
        for (long i = j; i < m; ++i)
        {
          if (G(i, j) != 0)
          {
            entries.emplace_back(used[i], used[j], G(i, j));
            if (i != j)
            {
              entries.emplace_back(used[j], used[i], G(i, j));
            }
          }
        }
      }
      parts[c].resize(Size, Size);
      parts[c].setFromTriplets(entries.begin(), entries.end());
      for (int column : used)
      {
        local[column] = -1;
      }
    }
  }
  for (const SparseMatrix& part : parts)
  {
    Sparse += part;
  }
}

SparseMatrix GramAccumulator::sum() const
{
  if (DenseLower.size() == 0)
  {
    return Sparse;
  }
  // both triangles of the dense part, written column by column
  SparseMatrix dense(Size, Size);
  dense.resizeNonZeros(Size * Size);
  for (long j = 0; j < Size; ++j)
  {
    dense.outerIndexPtr()[j] = static_cast<int>(j * Size);
    for (long i = 0; i < Size; ++i)
    {
      dense.innerIndexPtr()[j * Size + i] = static_cast<int>(i);
      dense.valuePtr()[j * Size + i] = i >= j ? DenseLower(i, j) : DenseLower(j, i);
    }
  }
  dense.outerIndexPtr()[Size] = static_cast<int>(Size * Size);
  return Sparse.nonZeros() == 0 ? dense : SparseMatrix(dense + Sparse);
}

namespace
{
template <typename Rows>
SparseMatrix gramOf(const Rows& A, long begin, long end, const Eigen::VectorXd& rowWeight)
{
  GramAccumulator gram(A.cols());
  gram.add(A, begin, end, rowWeight);
  return gram.sum();
}
}

SparseMatrix weightedGram(const SparseRowMatrix& A, long begin, long end, const Eigen::VectorXd& rowWeight)
{
  return gramOf(A, begin, end, rowWeight);
}

SparseMatrix weightedGram(const GatheredRows& A, long begin, long end, const Eigen::VectorXd& rowWeight)
{
  return gramOf(A, begin, end, rowWeight);
}

namespace
{
// Phi at the positions in row blocks (Phi_ij = phi_j(x_i)), each entry rounded to PhiValue
// whatever Block holds it: the same Phi wherever it is evaluated.
template <typename Block>
RowBlocksOf<Block> phiBlocks(const ShapeFunctions& basis, const PointList& positions, std::vector<int>* outside, const Progress& progress)
{
  return assembleRows<Block>(
    basis, positions, 1, false,
    [](long, const ShapeFunctionValues& phi, std::vector<std::vector<double>>& rows) {
      std::transform(phi.value.begin(), phi.value.end(), rows[0].begin(),
        [](double v) { return static_cast<double>(static_cast<PhiValue>(v)); });
    },
    outside, progress);
}
}

RowBlocks subspaceBlocks(const ShapeFunctions& basis, const PointList& positions, std::vector<int>* outside, const Progress& progress)
{
  return phiBlocks<PhiBlock>(basis, positions, outside, progress);
}

std::vector<long> positionsAmong(const PointList& points, const PointList& positions)
{
  // each point looks its position up among the positions' distinct ones (in parallel), then the
  // first point of each is taken in point order
  const PositionIndex index(positions);
  std::vector<long> numberOf(points.size());
#pragma omp parallel for schedule(static)
  for (long p = 0; p < static_cast<long>(points.size()); ++p)
  {
    numberOf[p] = index.find(points[p]);
  }
  std::vector<long> first(index.distinct().size(), -1);
  for (long p = 0; p < static_cast<long>(points.size()); ++p)
  {
    if (numberOf[p] >= 0 && first[numberOf[p]] < 0)
    {
      first[numberOf[p]] = p;
    }
  }
  std::vector<long> found(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
  {
    found[i] = first[index.numbers()[i]];
  }
  return found;
}

SparseRowMatrix subspaceMatrix(const ShapeFunctions& basis, const PointList& positions, std::vector<int>* outside, const Progress& progress)
{
  return concatenate(phiBlocks<SparseRowMatrix>(basis, positions, outside, progress));
}

const long* GatheredRows::order(long begin, long end) const
{
  if (!std::binary_search(Segments.begin(), Segments.end(), begin) || !std::binary_search(Segments.begin(), Segments.end(), end))
  {
    throw std::logic_error("a product over rows " + std::to_string(begin) + " to " + std::to_string(end) +
      " of gathered rows, not a run of their segments");
  }
  return Order.empty() ? nullptr : Order.data() + begin;
}

GatheredRows gatherRows(const ShapeFunctions& basis, const PointList& positions, const KnownRows& known, std::vector<int>* outside,
  const std::vector<long>& segments, bool storageOrder)
{
  const bool usable = known.known && known.row.size() == positions.size();
  // Phi evaluated at the positions without a known row, then every row viewed in the positions' order
  PointList missing;
  std::vector<long> missingIndex;
  for (std::size_t i = 0; i < positions.size(); ++i)
  {
    if (!usable || known.row[i] < 0)
    {
      missing.push_back(positions[i]);
      missingIndex.push_back(static_cast<long>(i));
    }
  }
  GatheredRows A;
  std::vector<int> outsideMissing;
  A.Own = std::make_unique<RowBlocks>(subspaceBlocks(basis, missing, &outsideMissing));
  if (outside)
  {
    for (int m : outsideMissing)
    {
      outside->push_back(static_cast<int>(missingIndex[m]));
    }
  }
  A.Columns = static_cast<long>(basis.size());
  A.Rows.resize(positions.size());
  long next = 0;
  for (std::size_t i = 0; i < positions.size(); ++i)
  {
    A.Rows[i] = usable && known.row[i] >= 0 ? rowOf(*known.known, known.row[i]) : rowOf(*A.Own, next++);
  }
  // each segment's rows by where their entries lie (std::less orders pointers into any arrays)
  A.Segments = segments.empty() ? std::vector<long>{ 0, A.rows() } : segments;
  if (A.Segments.front() != 0 || A.Segments.back() != A.rows() || !std::is_sorted(A.Segments.begin(), A.Segments.end()))
  {
    throw std::invalid_argument("gatherRows: the segments do not cover the positions in order");
  }
  if (!storageOrder)
  {
    return A;
  }
  A.Order.resize(positions.size());
  std::iota(A.Order.begin(), A.Order.end(), 0L);
  for (std::size_t s = 0; s + 1 < A.Segments.size(); ++s)
  {
    std::sort(A.Order.begin() + A.Segments[s], A.Order.begin() + A.Segments[s + 1],
      [&](long a, long b) { return std::less<const PhiValue*>()(A.Rows[a].value, A.Rows[b].value); });
  }
  return A;
}

EnergyNormals normalMatrices(const DeformationEnergy& energy)
{
  auto gram = [](const SparseRowMatrix& A) { return weightedGram(A, 0, A.rows(), Eigen::VectorXd::Ones(A.rows())); };
  return { gram(energy.stretch), gram(energy.bend), energy.bend.rows(), energy.ridge };
}

EnergyNormals volumetricEnergyNormals(const ShapeFunctions& basis, const PointList& integrationPoints, const std::vector<double>& volume,
  double gradientScale, double laplacianScale, const Progress& progress)
{
  const long n = static_cast<long>(integrationPoints.size()), k = static_cast<long>(basis.size());
  // points per block: about 8M shape function values (64 MB dense), and at least 1024 points:
  // a dense block updates the whole k x k triangle, which costs memory traffic ~k^2 however
  // few rows it has, so it must be tall to run at the BLAS's arithmetic speed
  const long block = std::max(1024L, (1L << 23) / std::max(1L, k));
  // the blocks taken along the Z-order curve: a block's points are near each other and meet few
  // samples (the points come from a farthest-point selection, the most spread order there is: a
  // block of 1024 of a 20k-point case's integration points met 7,000 of its 10,000 samples, and
  // the blocks' Grams, dense over those, made the set-up 42 s; 12 s in this order)
  const std::vector<int> order = zOrder(integrationPoints, 0, n);
  GramAccumulator stretch(k), bend(k);
  for (long first = 0; first < n; first += block)
  {
    const long last = std::min(n, first + block);
    PointList points;
    for (long i = first; i < last; ++i)
    {
      points.push_back(integrationPoints[order[i]]);
    }
    progress.stopIfAsked();
    const Progress part = progress.part(static_cast<double>(first) / n, static_cast<double>(last) / n);
    // rows 4i..4i+2: the gradient at q_i, row 4i+3: the Laplacian; then split into G and L
    SparseRowMatrix D = concatenate(assembleRows<SparseRowMatrix>(
      basis, points, 4, true,
      [&](long i, const ShapeFunctionValues& phi, std::vector<std::vector<double>>& rows) {
        const double g = std::sqrt(volume[order[first + i]]) * gradientScale, l = std::sqrt(volume[order[first + i]]) * laplacianScale;
        for (std::size_t a = 0; a < phi.index.size(); ++a)
        {
          for (int d = 0; d < 3; ++d)
          {
            rows[d][a] = g * phi.gradient[a][d];
          }
          rows[3][a] = l * phi.laplacian[a];
        }
      },
      nullptr, part));
    const SparseRowMatrix G = selectRows(D, [](long row) { return row % 4 != 3; });
    const SparseRowMatrix L = selectRows(D, [](long row) { return row % 4 == 3; });
    D = SparseRowMatrix(); // freed before the products
    stretch.add(G, 0, G.rows(), Eigen::VectorXd::Ones(G.rows()));
    bend.add(L, 0, L.rows(), Eigen::VectorXd::Ones(L.rows()));
  }
  return { stretch.sum(), bend.sum(), n, 0.0 };
}
} // namespace mlsdeform
