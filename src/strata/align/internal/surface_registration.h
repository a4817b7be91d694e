#pragma once
// Global registration of two keyframe surfaces (surface_descriptor.h) without an initial pose:
// FPFH correspondences (mutual nearest neighbours, exact L2), then RANSAC over triples of them
// with an edge-length pre-rejection (as PCL's SampleConsensusPrerejective: a triple whose
// pairwise distances disagree between the two clouds is dropped before it is scored), the
// rigid fit of a triple by Umeyama without scale, refined on the inliers of the best.
// Deterministic (a fixed seed). Thread safety: free function, no shared state.
#include <Eigen/Geometry>

#include "strata/align/surface_descriptor.h"

namespace strata::align::detail {

struct SurfaceRegistrationConfig {
  int iterations = 4000;          // RANSAC triples drawn
  double inlier_m = 0.08;         // a correspondence within this of the fit is an inlier
  double edge_similarity = 0.9;   // pre-rejection: shorter / longer edge of a triple at least this
  double min_edge_m = 0.15;       // triples with a shorter edge are degenerate
};

struct SurfaceRegistration {
  bool found = false;
  Eigen::Isometry3d T_a_b = Eigen::Isometry3d::Identity();
  int correspondences = 0;  // mutual FPFH nearest neighbours
  int inliers = 0;          // of the refined fit
};

SurfaceRegistration registerSurfaces(const KeyframeSurface& a, const KeyframeSurface& b,
                                     const SurfaceRegistrationConfig& config);

}  // namespace strata::align::detail
