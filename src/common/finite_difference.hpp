#pragma once
/// The finite-difference step rules of the library (shooting and inverse Jacobians, the test
/// support's derivative checks): a relative step times the variable's scale,
///   forward  h = sqrt(eps) * scale   (truncation O(h), round-off O(eps/h): error ~1e-8),
///   central  h = eps^(1/3) * scale   (truncation O(h^2), round-off O(eps/h): error ~1e-10),
/// each balancing truncation against round-off. Callers then take h = (x + h) - x, the step
/// actually realised in floating point.
namespace tcasim::fd {

/// sqrt(eps) for double.
inline constexpr double kForwardRelativeStep = 1.4901161193847656e-08;
/// eps^(1/3) for double.
inline constexpr double kCentralRelativeStep = 6.0554544523933395e-06;

/// The relative step of forward (false) or central (true) differences.
constexpr double relative_step(bool central) {
  return central ? kCentralRelativeStep : kForwardRelativeStep;
}

}  // namespace tcasim::fd
