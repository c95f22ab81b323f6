// A region's positions gathered from every process into one canonical order: the same list
// (and so the same deformation) however the dataset is split over processes or ordered, and
// each position once, however many pieces or blocks hold it.
#pragma once

#include "Common/Collective.h"
#include "Common/CoreTypes.h"

namespace mlsdeform
{
struct GatheredPositions
{
  PointList positions;
  std::vector<int> sets;    // the set of each position (0 .. setCount-1), or empty: one set
  int setCount = 1;
  std::vector<long> source; // each position's index in the process-ordered concatenation of the local lists
};

/// Gathers the positions of all processes (with sets: the set of each local position, numbered
/// per process, or, when negative, a set of the same number on every process (a block of a
/// region selected by name, split over processes); empty: one set) and orders them: sorted by coordinates, equal positions once;
/// with sets, each set's positions sorted and once, the sets ordered by their position lists
/// and equal sets once, numbered in that order.
GatheredPositions gatherPositions(const PointList& local, const std::vector<int>& localSets, const Collective& group);

/// Values given per local position (components each, row after row) in the gathered order.
std::vector<double> gatherValues(const double* local, long count, int components, const GatheredPositions& order,
  const Collective& group);
}
