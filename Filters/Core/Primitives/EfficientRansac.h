// Automatic detection of planes, cylinders, spheres and cones in oriented samples (paper section
// 6.3): the efficient RANSAC of Schnabel, Wahl and Klein 2007 ("Efficient RANSAC for point-cloud
// shape detection", Computer Graphics Forum 26(2), [39]) followed by a forward-search refinement
// of every primitive it extracts (ForwardSearch.h, [40, 41]).
//   - Localized sampling (section 4.3): a minimal set is the first sample drawn at random and two
//     more from the octree cell around it at a random level; the levels that produced good
//     candidates are drawn more often.
//   - Score (section 4.4): the samples within epsilon of a candidate whose normal deviates by
//     less than the normal threshold, restricted to the largest connected component among them
//     (cells of size clusterEpsilon that touch; for mesh faces also faces sharing a vertex,
//     since a coarse mesh's faces lie farther apart than clusterEpsilon); estimated on growing
//     random subsets with a confidence interval (section 4.5) and refined only for the best
//     candidates. The subsets are ranges of one random order of the samples; an extraction
//     removes its members from them and from every candidate's compatible samples, so the
//     scores stay current without being evaluated again.
//   - Probabilistic stopping (section 4.2): the best candidate, of n samples, is extracted once
//     1 - (1 - n / (N L 4))^T >= probability after T minimal sets (N samples left, L octree
//     levels); once a shape of minimumSupport samples would have been found with that
//     probability, no more sets are drawn and the search ends with the candidates left.
// Spheres and cylinders of a radius above the samples' bounding-box diagonal (planes or free
// forms within epsilon) and cones outside the angle range of Primitives.h are not kept.
// Extraction refits the best candidate to its compatible component by least squares (twice, which
// lets an inexact candidate from noisy normals grow onto its surface), then the forward search
// settles its members and parameters. The simplest primitive that explains the members as well
// takes its place: a plane, when the curved primitive bends over them by less than the forward
// search's admission distance or Schwarz's information criterion prefers the plane (on the
// vertices of their faces if faces are given: the independent observations), or else a curved
// primitive of fewer parameters that the criterion prefers (a sphere for a cone drawn on a noisy
// band of a sphere), which grows anew. A candidate whose extraction fails takes with it the
// candidates of its type drawn in the same component whose compatible samples all lie there.
// After the extraction, a curved primitive whose members planes found among them explain as well
// (the same criterion) becomes those planes (a cone tangent to two faces of a box, found before
// their planes); then every primitive gathers again the connected samples within its admission
// distance and either within its noise-aware admission angle or with all the vertices of their
// faces within the admission distance of the vertex noise (a face not much wider than the noise,
// whose normal is the noise's: a fan's thin triangle at a pole or an apex) (Schnabel et al.'s
// refitting); a primitive that the others explain but for fewer than minimumSupport members goes
// (a piece of a surface that noise split off, a cone tangent to two faces), and samples no
// primitive holds join the one that explains them, or else one they are compatible with (within
// epsilon and the normal threshold) in a connected component of its members. Then the same search
// runs once more on the samples left, which finds what the draws over all samples missed, and its
// primitives are settled with the others. Last, samples left just beyond epsilon of a primitive
// (within 2 epsilon, the vertices of their faces too) are the ends of its surface that least
// squares left out (a blend's ends): the minimax fit of its members and them replaces its shape
// when more of them lie within epsilon of it, and they join it. Deterministic for a seed: the
// random draws of a search are serial; the scoring, and the searches for planes among several
// curved primitives, run in parallel.
#pragma once

#include "Primitives/ForwardSearch.h"

#include <cstdint>

namespace mlsdeform
{
struct RansacParameters
{
  bool planes = true, cylinders = true, spheres = true, cones = true;
  double epsilon = 0;          // distance tolerance (absolute)
  double clusterEpsilon = 0;   // connectivity of a primitive's samples (absolute)
  double normalThreshold = 0;  // largest normal deviation (radians)
  int minimumSupport = 1;      // fewest samples of a primitive
  double probability = 0.95;   // of finding a shape of minimumSupport samples
  std::uint64_t seed = 0;
};

struct DetectedPrimitive
{
  Primitive shape;
  std::vector<int> members; // sample indices, increasing
  double rmsDistance = 0, maxDistance = 0;
};

/// The faces that the samples stand for (FaceSamples.h): the vertex indices of each sample's
/// face, and the vertices.
struct SampleFaces
{
  std::vector<std::vector<int>> faces;
  PointList vertices;
};

/// Primitives in the oriented samples (points with unit normals), in the order found; a sample
/// belongs to at most one. Samples whose normal is not a finite unit vector take part in none.
/// faces (optional): the face each sample stands for; faces sharing a vertex are connected, and
/// a face joins a primitive beyond epsilon (its ends) only when all its vertices lie near it.
/// Throws InvalidInputException for non-finite points, mismatched sizes, vertex indices out of
/// range or invalid parameters.
std::vector<DetectedPrimitive> detectPrimitives(const PointList& points, const std::vector<Vec3>& normals,
  const RansacParameters& parameters, const SampleFaces* faces = nullptr, const Progress& progress = {});
} // namespace mlsdeform
