// Sparse matrices of the MLS subspace evaluated at positions (paper sections 4 and 5):
//   Phi_ij = phi_j(x_i)                                   (d = Phi w)
//   G_{3i+d, j} = sqrt(V_i) d phi_j(q_i)/dx_d             (eq. 12, E_stretch = |G w|^2)
//   L_{i,j}     = sqrt(V_i) Laplacian phi_j(q_i)          (eq. 13, E_bend    = |L w|^2)
#pragma once

#include "Basis/ShapeFunctions.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <type_traits>

namespace mlsdeform
{
/// Phi's entries: single precision, wherever Phi is evaluated (subspaceBlocks, gatherRows and
/// subspaceMatrix alike, so that every operator meets the same Phi). Phi is about 70-90 entries a
/// row on a CFD mesh, the larger part of a set-up's memory. A float rounds a shape function's
/// value by at most 2^-24 relative, which moves a point by at most 6e-8 of the nearby samples'
/// displacements, far below the MLS discretization's own error; the output stays an exact linear
/// map of w (derivatives and exact targets exact). The rows kept for every point hold floats;
/// operators assembled once for the k x k systems hold doubles.
using PhiValue = float;
/// An entry's column as its place in its rows' table of columns (PhiRows).
using PhiPlace = std::uint16_t;

/// Rows of Phi at consecutive positions that share one table of the columns they use: an entry
/// holds its column's place in the table (16 bits) and its value (a float), 6 bytes where a
/// sparse matrix's entry takes 8 (a 4096-point block of a CFD mesh meets a few hundred of the k
/// samples). With 32-bit columns the 1M-cell hull case's first variant peaked at 1,539 MiB, so
/// at 1,375 MiB; the 400k-point one's heap at 617 MB, so at 550 MB.
struct PhiRows
{
  std::vector<int> columns;    // the columns the rows use, in the order first met (at most 65536)
  std::vector<PhiPlace> place; // per entry: its column's place in columns
  std::vector<PhiValue> value; // per entry
  std::vector<int> start;      // per row and one more: the row's first entry
  long rows() const { return static_cast<long>(start.size()) - 1; }
};

/// A block of Phi's rows: PhiRows that follow each other, one unless the block's rows use more
/// than 65536 columns.
struct PhiBlock
{
  std::vector<PhiRows> parts;
  long rows() const
  {
    long rows = 0;
    for (const PhiRows& part : parts)
    {
      rows += part.rows();
    }
    return rows;
  }
};

/// A sparse matrix kept as blocks of consecutive rows (row-major sparse matrices or PhiBlocks),
/// each of rowsPerBlock rows (the last may hold fewer): rows evaluated in parallel chunks stay where they were
/// assembled. Phi at a 1M-point mesh (80M entries) copied into one matrix doubled the peak memory.
template <typename Block>
struct RowBlocksOf
{
  std::vector<Block> blocks;
  long rowsPerBlock = 1;
  long columns = 0;
  long rows() const
  {
    long rows = 0;
    for (const Block& block : blocks)
    {
      rows += block.rows();
    }
    return rows;
  }
};
using RowBlocks = RowBlocksOf<PhiBlock>;

/// Row i of Phi's row blocks: entry a is column columns[place[a]] = column(a), value value[a].
struct PhiRowSpan
{
  const PhiPlace* place = nullptr;
  const int* columns = nullptr; // the table of its PhiRows
  const PhiValue* value = nullptr;
  long size = 0;
  long columnCount = 0; // of the table
  int column(long a) const { return columns[place[a]]; }
  const PhiPlace* entryColumns() const { return place; }
};

/// Phi at the positions (one row each), as row blocks. Rows of positions outside every support
/// are empty; their indices are appended to outside when given. Throws AbortedException when
/// progress asks to stop (checked after each block of positions).
RowBlocks subspaceBlocks(const ShapeFunctions& basis, const PointList& positions, std::vector<int>* outside = nullptr, const Progress& progress = {});

/// Phi rows evaluated before at some positions (with the same shape functions), to be used
/// rather than evaluated again: row[i] is the row of `known` that holds Phi at the i-th
/// position, or -1.
struct KnownRows
{
  const RowBlocks* known = nullptr;
  std::vector<long> row;
};

/// For each position, the first index of points at exactly that position (+0 = -0), or -1.
std::vector<long> positionsAmong(const PointList& points, const PointList& positions);

/// Phi at the positions as one matrix (the entries of subspaceBlocks, held as doubles).
SparseRowMatrix subspaceMatrix(
  const ShapeFunctions& basis, const PointList& positions, std::vector<int>* outside = nullptr, const Progress& progress = {});

/// Phi at positions, each row a view: of a row of the known rows (evaluating Phi at a position
/// gives the same bits wherever it is done) or of a row evaluated for it and kept here. A region
/// of mesh points costs no copy of its rows (115 MB for the patches of the 1M-cell hull case).
/// The views stay valid while the known rows live unchanged.
///
/// multiplyRows reads the rows in the order they are stored (order()), within each segment of
/// consecutive rows (a region's): a region's points in the mesh's order meet Phi's rows (in the
/// samples' spatial order) in another block at nearly every row, and a pass over a 1M-point
/// sphere's regions' 410k rows took longer than over all 1M rows. Each row's sum is the same in
/// any order of rows; sums over rows (multiplyTransposed) keep the rows' order. A product's
/// range of rows is a run of whole segments.
class GatheredRows
{
public:
  long rows() const { return static_cast<long>(Rows.size()); }
  long cols() const { return Columns; }
  const PhiRowSpan& row(long i) const { return Rows[i]; }
  /// The rows begin..end - 1 in storage order (a permutation of them), or null when gathered
  /// without it (in turn); throws std::logic_error when the range is not a run of whole segments.
  const long* order(long begin, long end) const;

private:
  friend GatheredRows gatherRows(const ShapeFunctions&, const PointList&, const KnownRows&, std::vector<int>*, const std::vector<long>&, bool);
  std::unique_ptr<RowBlocks> Own; // the rows evaluated here (on the heap: the views outlive a move)
  std::vector<PhiRowSpan> Rows;
  std::vector<long> Order;    // per segment, its rows by where their entries are stored (or empty: in turn)
  std::vector<long> Segments; // the first row of each segment, and the end
  long Columns = 0;
};

/// Phi at the positions, the rows in `known` viewed, the others evaluated (indices of positions
/// outside every support appended to outside). segments: the first position of each segment of
/// positions, and the end (empty: one segment). storageOrder: each segment's rows are sorted by
/// where they are stored, for multiplyRows; without it (rows only summed over, as a gradient's:
/// the sort took half the gathering of 70k rows) they are read in turn.
GatheredRows gatherRows(const ShapeFunctions& basis, const PointList& positions, const KnownRows& known, std::vector<int>* outside = nullptr,
  const std::vector<long>& segments = {}, bool storageOrder = true);

/// Row i of a row-major sparse matrix: its column indices and values (column(a) and value[a],
/// the one way the products below read a row, as they read PhiRowSpan's).
template <typename Scalar>
struct RowSpan
{
  const int* index;
  const Scalar* value;
  long size;
  int column(long a) const { return index[a]; }
  const int* entryColumns() const { return index; }
};
template <typename Scalar>
RowSpan<Scalar> rowOf(const Eigen::SparseMatrix<Scalar, Eigen::RowMajor>& A, long i)
{
  const long begin = A.outerIndexPtr()[i];
  return { A.innerIndexPtr() + begin, A.valuePtr() + begin, A.outerIndexPtr()[i + 1] - begin };
}
inline PhiRowSpan rowOf(const RowBlocks& A, long i)
{
  long r = i % A.rowsPerBlock;
  for (const PhiRows& part : A.blocks[i / A.rowsPerBlock].parts)
  {
    if (r < part.rows())
    {
      const int begin = part.start[r];
      return { part.place.data() + begin, part.columns.data(), part.value.data() + begin, part.start[r + 1] - begin,
        static_cast<long>(part.columns.size()) };
    }
    r -= part.rows();
  }
  return {}; // not reached for a row of A
}
inline const PhiRowSpan& rowOf(const GatheredRows& A, long i)
{
  return A.row(i);
}

/// Asks for a row's entries to be brought into the cache: the rows a gradient's product reads
/// are in its positions' order, scattered over Phi's storage, and fetching the next row's while
/// this one is summed made the hull case's constraint chain 20% faster.
template <typename Span>
void prefetch(const Span& row)
{
  constexpr long Line = 64;
  const char* values = reinterpret_cast<const char*>(row.value);
  for (long b = 0; b < row.size * static_cast<long>(sizeof(*row.value)); b += Line)
  {
    __builtin_prefetch(values + b);
  }
  const char* columns = reinterpret_cast<const char*>(row.entryColumns());
  for (long b = 0; b < row.size * static_cast<long>(sizeof(*row.entryColumns())); b += Line)
  {
    __builtin_prefetch(columns + b);
  }
}

/// Whether a product's rows are written to out or added to what out holds.
enum class Into
{
  Write,
  Add,
};

/// The rows of a dense X with three columns that a product's entries read, as (x, y, z) triples
/// in one array, so that an entry's x, y and z share a cache line and an entry needs no lookup
/// in its rows' table of columns: for rows of Phi (PhiRowSpan), read in storage order, X at their
/// table's columns (PhiRows), gathered again when a row's table is another's (a few hundred
/// columns for 4096 consecutive rows), read by place; for a sparse matrix's rows all of X, read by
/// column.
template <typename Dense>
class GatheredX
{
public:
  explicit GatheredX(const Eigen::MatrixBase<Dense>& X)
    : X(X)
  {
  }
  const double* of(const PhiRowSpan& row)
  {
    if (row.columns != Table)
    {
      Table = row.columns;
      Values.resize(3 * static_cast<std::size_t>(row.columnCount));
      for (long p = 0; p < row.columnCount; ++p)
      {
        for (int c = 0; c < 3; ++c)
        {
          Values[3 * p + c] = X(row.columns[p], c);
        }
      }
    }
    return Values.data();
  }
  template <typename Scalar>
  const double* of(const RowSpan<Scalar>&)
  {
    if (Values.empty())
    {
      Values.resize(3 * static_cast<std::size_t>(X.rows()));
      Eigen::Map<PointDisplacements>(Values.data(), X.rows(), 3) = X;
    }
    return Values.data();
  }
  static long at(const PhiRowSpan& row, long a) { return row.place[a]; }
  template <typename Scalar>
  static long at(const RowSpan<Scalar>& row, long a)
  {
    return row.index[a];
  }

private:
  const Eigen::MatrixBase<Dense>& X;
  const int* Table = nullptr;
  std::vector<double> Values;
};

/// The rows begin..end - 1 of A in the order multiplyRows reads them (GatheredRows' storage
/// order; other rows in turn): the n-th is rows[n - begin], or n when rows is null.
template <typename Rows>
const long* readingOrder(const Rows&, long, long)
{
  return nullptr;
}
inline const long* readingOrder(const GatheredRows& A, long begin, long end)
{
  return A.order(begin, end);
}

/// Rows of a product A X multiplied before, elsewhere: row i of A X is known[3 * row[i]] .. + 2
/// where row[i] >= 0 (rows of Phi viewed from the rows that product was taken over).
struct KnownProduct
{
  const std::vector<long>* row = nullptr;
  const double* known = nullptr;
};

/// Rows begin..end of A X for a dense X with three columns (either storage order), written as
/// (x, y, z) triples to out (or added to them, Into::Add): one parallel pass over those rows of A
/// (d(x_i) = sum_j Phi_ij w_j at many points). Each entry is summed by one thread in the order of
/// its row, so the result does not depend on the number of threads. Rows are taken in chunks as
/// threads come free (a virtual CPU at times runs at half speed: an even split would wait for it).
/// Rows in `known` are copied from it, the same bits (Write only).
template <typename Rows, typename Dense>
void multiplyRows(const Rows& A, const Eigen::MatrixBase<Dense>& X, long begin, long end, double* out, Into into = Into::Write,
  const KnownProduct& known = {})
{
  const long* order = readingOrder(A, begin, end);
#pragma omp parallel
  {
    GatheredX<Dense> gathered(X);
#pragma omp for schedule(dynamic, 1024)
    for (long n = begin; n < end; ++n)
    {
      const long i = order ? order[n - begin] : n;
      if (known.row && (*known.row)[i] >= 0)
      {
        std::copy_n(known.known + 3 * (*known.row)[i], 3, out + 3 * (i - begin));
        continue;
      }
      const auto& row = rowOf(A, i);
      const double* g = gathered.of(row);
      double x = 0, y = 0, z = 0;
      for (long a = 0; a < row.size; ++a)
      {
        const double v = row.value[a];
        const double* r = g + 3 * gathered.at(row, a);
        x += v * r[0];
        y += v * r[1];
        z += v * r[2];
      }
      double* o = out + 3 * (i - begin);
      if (into == Into::Add)
      {
        o[0] += x;
        o[1] += y;
        o[2] += z;
      }
      else
      {
        o[0] = x;
        o[1] = y;
        o[2] = z;
      }
    }
  }
}

/// A X for a dense X with three columns (multiplyRows over all rows).
template <typename Dense>
Displacements multiplyRows(const SparseRowMatrix& A, const Eigen::MatrixBase<Dense>& X)
{
  PointDisplacements out(A.rows(), 3);
  multiplyRows(A, X, 0, A.rows(), out.data());
  return out;
}

/// sum_i A_i^T x_i (k x columns, row-major) over the rows i of A(begin:end, :) that
/// visit(lo, hi, add) hands to add(i, x_i, next) in ascending order, for each block [lo, hi) of
/// rows (x_i a row of values; next: the row add gets next, or -1, whose entries are fetched
/// meanwhile): partial sums over fixed blocks of rows, added in block order, so that the result
/// does not depend on the number of threads.
template <int Columns, typename Rows, typename Visit>
Eigen::Matrix<double, Eigen::Dynamic, Columns, Eigen::RowMajor> blockTransposedSum(
  const Rows& A, long begin, long end, long columns, Visit visit)
{
  using Product = Eigen::Matrix<double, Eigen::Dynamic, Columns, Eigen::RowMajor>;
  constexpr long Block = 8192;
  const long blocks = (end - begin + Block - 1) / Block;
  std::vector<Product> partial(static_cast<std::size_t>(blocks)); // a row's columns side by side
#pragma omp parallel for schedule(dynamic)
  for (long b = 0; b < blocks; ++b)
  {
    Product& sum = partial[b];
    sum.setZero(A.cols(), columns);
    visit(begin + b * Block, std::min(end, begin + (b + 1) * Block), [&](long i, const auto& x, long next) {
      const auto& row = rowOf(A, i);
      if (next >= 0)
      {
        prefetch(rowOf(A, next));
      }
      for (long a = 0; a < row.size; ++a)
      {
        sum.row(row.column(a)) += static_cast<double>(row.value[a]) * x;
      }
    });
  }
  Product product = Product::Zero(A.cols(), columns);
  for (const Product& sum : partial)
  {
    product += sum;
  }
  return product;
}

/// A(begin:end, :)^T X (k x X's columns, row-major) for a dense X with one row per row of the
/// range (b_r = Phi_r^T dbar_r; three columns, or several functions' side by side), without a
/// transposed copy of A (blockTransposedSum). The rows are summed in their own order, not in
/// GatheredRows' storage order: that depends on where the rows lie in memory, which differs
/// between processes and runs.
///
/// skipZeroRows: X's zero rows are passed over without reading A's rows; the sums are the same.
template <typename Rows, typename Dense>
Eigen::Matrix<double, Eigen::Dynamic, Dense::ColsAtCompileTime, Eigen::RowMajor> multiplyTransposed(
  const Rows& A, long begin, long end, const Eigen::MatrixBase<Dense>& X, bool skipZeroRows = false)
{
  static_assert(Dense::ColsAtCompileTime != 1, "X has several columns");
  return blockTransposedSum<Dense::ColsAtCompileTime>(A, begin, end, X.cols(), [&](long lo, long hi, const auto& add) {
    for (long i = lo; i < hi; ++i)
    {
      if (!skipZeroRows || !(X.row(i - begin).array() == 0).all())
      {
        add(i, X.row(i - begin), i + 1 < end ? i + 1 : -1);
      }
    }
  });
}

/// A^T X_f for several functions' X_f given by their non-zero rows (rows of A, ascending per
/// function; SparseGradients): those on at least a quarter of A's rows in one product, their
/// columns side by side (an entry of A is read once for all of them: the hull case's area, volume
/// and fluid volume), each other over its own rows alone (a thickness on a few rows). Each sum
/// is the one multiplyTransposed gives for X_f (zero elsewhere) alone.
template <typename Rows>
std::vector<PointDisplacements> multiplyTransposedEach(const Rows& A, const SparseGradients& X)
{
  std::vector<PointDisplacements> out(X.functions());
  std::vector<std::size_t> together;
  for (std::size_t f = 0; f < X.functions(); ++f)
  {
    const long first = X.starts[f], last = X.starts[f + 1];
    if (4 * (last - first) >= A.rows() && A.rows() > 0)
    {
      together.push_back(f);
      continue;
    }
    out[f] = blockTransposedSum<3>(A, 0, A.rows(), 3, [&](long lo, long hi, const auto& add) {
      const auto from = std::lower_bound(X.rows.begin() + first, X.rows.begin() + last, lo) - X.rows.begin();
      for (long e = from; e < last && X.rows[e] < hi; ++e)
      {
        add(X.rows[e], Eigen::Map<const Eigen::RowVector3d>(X.values.data() + 3 * e), e + 1 < last ? X.rows[e + 1] : -1);
      }
    });
  }
  if (!together.empty())
  {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> side =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>::Zero(A.rows(), 3 * together.size());
    for (std::size_t t = 0; t < together.size(); ++t)
    {
      for (long e = X.starts[together[t]]; e < X.starts[together[t] + 1]; ++e)
      {
        side.row(X.rows[e]).segment<3>(3 * t) = Eigen::Map<const Eigen::RowVector3d>(X.values.data() + 3 * e);
      }
    }
    const auto product = multiplyTransposed(A, 0, A.rows(), side, true);
    for (std::size_t t = 0; t < together.size(); ++t)
    {
      out[together[t]] = product.middleCols(3 * t, 3);
    }
  }
  return out;
}

/// A(begin:end, :)^T diag(rowWeight) A(begin:end, :) (rowWeight: one non-negative weight per row
/// of the range), the k x k Gram matrix of a row range (GramAccumulator on that one range).
SparseMatrix weightedGram(const SparseRowMatrix& A, long begin, long end, const Eigen::VectorXd& rowWeight);
SparseMatrix weightedGram(const GatheredRows& A, long begin, long end, const Eigen::VectorXd& rowWeight);

/// Sums Gram matrices A^T diag(weight) A of row blocks. A sparse block is multiplied by sparse
/// products over row chunks of a fixed size in parallel, summed in their order (the same result
/// whatever the number of threads); a mostly full block (a global basis) by the BLAS's
/// symmetric rank-k update (dsyrk, multithreaded and vectorized in OpenBLAS) into one dense
/// lower triangle, so that a dense k x k result costs k^2 doubles, not a copy per block.
class GramAccumulator
{
public:
  explicit GramAccumulator(long size);
  void add(const SparseRowMatrix& A, long begin, long end, const Eigen::VectorXd& rowWeight);
  void add(const GatheredRows& A, long begin, long end, const Eigen::VectorXd& rowWeight);
  /// The sum as a symmetric sparse matrix (both triangles).
  SparseMatrix sum() const;

private:
  template <typename Rows>
  void addRows(const Rows& A, long begin, long end, const Eigen::VectorXd& rowWeight);

  long Size;
  SparseMatrix Sparse;
  Eigen::MatrixXd DenseLower; // empty until a dense block came
};

/// The smoothness energies of a subspace as weighted rows: E_stretch = |G w|^2 and
/// E_bend = |L w|^2 (eq. 9, 11, 12, 13).
struct DeformationEnergy
{
  SparseRowMatrix stretch; // G
  SparseRowMatrix bend;    // L
  /// A ridge |w|^2 weighted by this fraction of the system's largest diagonal entry. Energies
  /// measured at few points (eq. 11 at the vertices) leave combinations of shape functions that
  /// move none of those points undetermined (more shape functions than vertices, or a global
  /// basis's z polynomial on a plane z = const); the ridge picks the smallest. 0: none.
  double ridge = 0;
};

/// What the normal equations (eq. 14) need of the energies: G^T G and L^T L (k x k).
struct EnergyNormals
{
  SparseMatrix stretch; // G^T G
  SparseMatrix bend;    // L^T L
  long points = 0;      // the points the bending energy is measured at (rows of L)
  double ridge = 0;     // as DeformationEnergy::ridge
};

/// G^T G and L^T L of an energy given by its rows.
EnergyNormals normalMatrices(const DeformationEnergy& energy);

/// G^T G and L^T L for G (3N x k) and L (N x k) at the integration points q_i with volumes V_i
/// (eq. 12, 13): the gradient rows multiplied by sqrt(V_i) * gradientScale, the Laplacian rows
/// by sqrt(V_i) * laplacianScale. The rows are formed for a block of points at a time (the
/// derivatives evaluated once per point), multiplied into the normal matrices and dropped, so
/// a global basis needs memory ~k^2, not ~N k (Fig. 4 up to k = 10k). Throws AbortedException
/// when progress asks to stop.
EnergyNormals volumetricEnergyNormals(const ShapeFunctions& basis, const PointList& integrationPoints, const std::vector<double>& volume,
  double gradientScale, double laplacianScale, const Progress& progress = {});

} // namespace mlsdeform
