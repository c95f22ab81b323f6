#include "SubspaceOperators.h"

#include <omp.h>

namespace mlsdeform
{
namespace
{
// Assembles a row-major sparse matrix with rowsPerPoint rows per position, evaluated in
// parallel chunks; fill(i, values, rows) writes the rows of position i from its shape functions.
template <typename Fill>
SparseRowMatrix assembleRows(const ShapeFunctions& basis, const PointList& positions, int rowsPerPoint, bool withDerivatives,
  Fill fill, std::vector<int>* outside, const Progress& progress)
{
  const long n = static_cast<long>(positions.size());
  constexpr long Chunk = 4096;
  const long chunks = (n + Chunk - 1) / Chunk;
  struct Part
  {
    std::vector<int> columns;
    std::vector<double> values;
    std::vector<int> rowLength;
    std::vector<int> outside;
  };
  std::vector<Part> parts(chunks);
  long done = 0;
#pragma omp parallel
  {
    ShapeFunctionValues phi;
    std::vector<std::vector<double>> rows(rowsPerPoint);
#pragma omp for schedule(dynamic)
    for (long c = 0; c < chunks; ++c)
    {
      Part& part = parts[c];
      for (long i = c * Chunk; i < std::min(n, (c + 1) * Chunk); ++i)
      {
        basis.evaluate(positions[i], phi, withDerivatives);
        if (phi.empty())
        {
          part.outside.push_back(static_cast<int>(i));
        }
        for (auto& row : rows)
        {
          row.resize(phi.index.size());
        }
        fill(i, phi, rows);
        for (const auto& row : rows)
        {
          part.columns.insert(part.columns.end(), phi.index.begin(), phi.index.end());
          part.values.insert(part.values.end(), row.begin(), row.end());
          part.rowLength.push_back(static_cast<int>(phi.index.size()));
        }
      }
#pragma omp atomic
      ++done;
      if (omp_get_thread_num() == 0)
      {
        progress.report(static_cast<double>(done) / chunks);
      }
    }
  }
  // Concatenate the chunks into compressed row storage.
  std::size_t nonZeros = 0;
  for (const Part& part : parts)
  {
    nonZeros += part.values.size();
  }
  SparseRowMatrix A(n * rowsPerPoint, static_cast<long>(basis.size()));
  A.resizeNonZeros(static_cast<long>(nonZeros));
  auto* outer = A.outerIndexPtr();
  std::size_t offset = 0, row = 0;
  outer[0] = 0;
  for (Part& part : parts)
  {
    std::copy(part.columns.begin(), part.columns.end(), A.innerIndexPtr() + offset);
    std::copy(part.values.begin(), part.values.end(), A.valuePtr() + offset);
    for (int length : part.rowLength)
    {
      outer[row + 1] = outer[row] + length;
      ++row;
    }
    offset += part.values.size();
    if (outside)
    {
      outside->insert(outside->end(), part.outside.begin(), part.outside.end());
    }
  }
  return A;
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

void multiplyRows(const SparseRowMatrix& A, const Displacements& X, long begin, long end, double* out)
{
  const auto* outer = A.outerIndexPtr();
  const auto* inner = A.innerIndexPtr();
  const double* value = A.valuePtr();
#pragma omp parallel for schedule(static)
  for (long i = begin; i < end; ++i)
  {
    double x = 0, y = 0, z = 0;
    for (auto a = outer[i]; a < outer[i + 1]; ++a)
    {
      const double v = value[a];
      const auto j = inner[a];
      x += v * X(j, 0);
      y += v * X(j, 1);
      z += v * X(j, 2);
    }
    double* o = out + 3 * (i - begin);
    o[0] = x;
    o[1] = y;
    o[2] = z;
  }
}

Displacements multiplyRows(const SparseRowMatrix& A, const Displacements& X)
{
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> out(A.rows(), 3);
  multiplyRows(A, X, 0, A.rows(), out.data());
  return out;
}

Displacements multiplyTransposed(const SparseRowMatrix& A, long begin, long end, const Displacements& X)
{
  return multiplyRows(SparseRowMatrix(A.middleRows(begin, end - begin).transpose()), X);
}

SparseMatrix weightedGram(const SparseRowMatrix& A, long begin, long end, const Eigen::VectorXd& rowWeight)
{
  // A mostly full range (a global basis) is multiplied as a dense matrix: Eigen's blocked,
  // multithreaded product is far faster there than sparse products.
  const SparseRowMatrix range = A.middleRows(begin, end - begin);
  if (range.nonZeros() > 0.25 * static_cast<double>(range.rows()) * static_cast<double>(range.cols()))
  {
    const Eigen::MatrixXd dense(range);
    const Eigen::MatrixXd gram = dense.transpose() * rowWeight.asDiagonal() * dense;
    return gram.sparseView();
  }
  const int chunks = std::max(1, omp_get_max_threads());
  std::vector<SparseMatrix> parts(chunks);
#pragma omp parallel for schedule(static, 1)
  for (int c = 0; c < chunks; ++c)
  {
    const long first = begin + (end - begin) * c / chunks, last = begin + (end - begin) * (c + 1) / chunks;
    const SparseRowMatrix rows = A.middleRows(first, last - first);
    parts[c] = SparseMatrix(rows.transpose() * rowWeight.segment(first - begin, last - first).asDiagonal() * rows);
  }
  SparseMatrix sum = parts[0];
  for (int c = 1; c < chunks; ++c)
  {
    sum += parts[c];
  }
  return sum;
}

SparseRowMatrix subspaceMatrix(const ShapeFunctions& basis, const PointList& positions, std::vector<int>* outside, const Progress& progress)
{
  return assembleRows(
    basis, positions, 1, false,
    [](long, const ShapeFunctionValues& phi, std::vector<std::vector<double>>& rows) { rows[0] = phi.value; },
    outside, progress);
}

DeformationEnergy volumetricEnergy(const ShapeFunctions& basis, const PointList& integrationPoints, const std::vector<double>& volume,
  double gradientScale, double laplacianScale, const Progress& progress)
{
  // Rows 4i..4i+2: the gradient at q_i, row 4i+3: the Laplacian; then split into G and L.
  const SparseRowMatrix D = assembleRows(
    basis, integrationPoints, 4, true,
    [&](long i, const ShapeFunctionValues& phi, std::vector<std::vector<double>>& rows) {
      const double g = std::sqrt(volume[i]) * gradientScale, l = std::sqrt(volume[i]) * laplacianScale;
      for (std::size_t a = 0; a < phi.index.size(); ++a)
      {
        for (int d = 0; d < 3; ++d)
        {
          rows[d][a] = g * phi.gradient[a][d];
        }
        rows[3][a] = l * phi.laplacian[a];
      }
    },
    nullptr, progress);
  DeformationEnergy energy;
  energy.stretch = selectRows(D, [](long row) { return row % 4 != 3; });
  energy.bend = selectRows(D, [](long row) { return row % 4 == 3; });
  return energy;
}
} // namespace mlsdeform
