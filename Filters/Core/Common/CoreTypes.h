// Plain C++17 + Eigen types shared by the deformation core (no VTK here).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <stdexcept>
#include <string>
#include <vector>

namespace mlsdeform
{
using Vec3 = Eigen::Vector3d;
using PointList = std::vector<Vec3>;
using SparseMatrix = Eigen::SparseMatrix<double>;       // column major, for the solver
using SparseRowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>; // rows = evaluation points
using Displacements = Eigen::Matrix<double, Eigen::Dynamic, 3>; // one row per point (or per shape function)
/// Displacements of points stored as (x, y, z) triples, VTK's layout: a VTK array is viewed, not copied.
using PointDisplacements = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using PointDisplacementsView = Eigen::Map<const PointDisplacements>;

/// The gradients of several functions, each at some rows (a process's points, or gathered
/// positions): function f's entries are starts[f] .. starts[f + 1] - 1, each a row (rows) and its
/// 3 values (values).
struct SparseGradients
{
  std::vector<long> rows;
  std::vector<double> values;
  std::vector<long> starts{ 0 };
  std::size_t functions() const { return starts.size() - 1; }
};

/// The one family of the plugin's exceptions: every VTK algorithm catches it at its boundary and
/// reports the message (and catches any other std::exception the same way).
struct Error : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Bad input (empty, NaN, degenerate, nothing selected): the caller reports it and keeps its data.
struct InvalidInputException : Error
{
  using Error::Error;
};

/// The linear system could not be solved (singular or not positive definite).
struct SolverException : Error
{
  using Error::Error;
};

/// The user cancelled a long computation (ParaView's progress bar); what finished is kept.
struct AbortedException : Error
{
  using Error::Error;
};

/// Reports the fraction [0,1] of a long computation; may be empty.
using ProgressCallback = void (*)(void* client, double fraction);
/// Whether the client asks a long computation to stop (a cancel); may be empty. Asked by the
/// calling thread (thread 0 of a parallel region), more often than progress is reported: the
/// client may take the request then (a GUI's cancel button).
using StopRequest = bool (*)(void* client);
struct Progress
{
  ProgressCallback callback = nullptr;
  void* client = nullptr;
  double begin = 0.0;
  double end = 1.0;
  StopRequest stop = nullptr;
  void report(double fraction) const
  {
    if (callback)
    {
      callback(client, begin + (end - begin) * fraction);
    }
  }
  /// The part [from, to] of this range (fractions of it), for the same client.
  Progress part(double from, double to) const { return { callback, client, begin + (end - begin) * from, begin + (end - begin) * to, stop }; }
  /// Whether the client asks to stop.
  bool stopping() const { return stop && stop(client); }
  /// Throws AbortedException when the client asks to stop: called between the steps of a long
  /// computation, outside parallel regions, where stopping leaves nothing half-built.
  void stopIfAsked() const
  {
    if (stopping())
    {
      throw AbortedException("cancelled");
    }
  }
};
} // namespace mlsdeform
