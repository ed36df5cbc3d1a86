#pragma once
/// Rigid obstacles fixed in the world and the gap between them and the rod's section
/// (docs/scenario-format.md "Obstacles", docs/conventions.md "Contact"). Both solvers take
/// the gap, its normal and the touching point of the section from section_gap, so they
/// solve the same contact problem and differ only in where they evaluate it.
///
/// The gap at s (the one definition both methods use; section_gaps gives its candidates):
/// circle section of radius r (and a custom section's contact circle):
///   g(s) = d(p) - r sqrt(1 - (n . t)^2),
/// d the obstacle's signed distance of the centerline point p = p(s) (negative inside),
/// n = grad d the obstacle's outward unit normal there, t = R e3: the distance of the
/// outline point farthest along -n. It is the plane distance of the lowest outline point
/// for a plane (exact), and exact for a cylinder, sphere or box whenever n lies in the
/// section plane, which holds where a smooth tube touches a smooth obstacle; elsewhere it
/// is the outline gap to second order in (section radius / obstacle radius).
/// Rectangle section: the exact distances of its four corners and, on a curved obstacle,
/// of the nearest interior point of each edge (section_gaps).
/// Each candidate's first variation under a body displacement dp and a world rotation
/// dtheta:
///   dg = n . dp + (c x n) . dtheta (+ c . dn, zero for a plane and for a circle with
///   n in the section plane), c = the touching point's offset from p (world),
/// so the contact force lambda n at p + c (lambda >= 0, the pressure's resultant) does the
/// virtual work lambda dg: force lambda n, moment c x (lambda n) about p.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "rod/profile.hpp"

namespace tcasim::rod {

struct RodModel;
struct Result;

/// One rigid obstacle (world frame W, SI).
struct Obstacle {
  enum class Type { kPlane, kCylinder, kSphere, kBox };
  std::string name;  ///< unique among the model's obstacles; names CSV columns
  Type type = Type::kPlane;
  /// plane: a point on it; cylinder: a point on its axis; sphere, box: the centre [m].
  Eigen::Vector3d point_W_m = Eigen::Vector3d::Zero();
  /// plane: the unit normal pointing into the free side; cylinder: the unit axis; else 0.
  Eigen::Vector3d direction_W = Eigen::Vector3d::UnitZ();
  double radius_m = 0.0;                                     ///< cylinder, sphere
  Eigen::Vector3d half_extents_m = Eigen::Vector3d::Zero();  ///< box, along its own axes
  Eigen::Matrix3d R_WO = Eigen::Matrix3d::Identity();        ///< box: columns are its axes in W
  double friction = 0.0;  ///< Coulomb mu (dynamics, grasps); statics are frictionless

  /// Signed distance of the world point x to the surface [m] (negative inside) and the
  /// outward unit normal at the nearest surface point (the gradient of the distance; inside
  /// a box, the normal of the nearest face; on a cylinder's axis or at a sphere's centre an
  /// arbitrary unit vector normal to the axis).
  struct Distance {
    double distance_m = 0.0;
    Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();
  };
  Distance distance(const Eigen::Vector3d& x_W_m) const;
};

const char* to_string(Obstacle::Type type);

/// The outline a section touches with at one s: a circle (radius), a rectangle (width
/// along body x, height along body y), or none (a custom section without contact_radius_m).
struct ContactOutline {
  enum class Kind { kNone, kCircle, kRectangle };
  Kind kind = Kind::kNone;
  double width_m = 0.0;   ///< circle: the diameter
  double height_m = 0.0;  ///< circle: the diameter
};

/// The outline of `model`'s section at s: a circle of the local diameter, a rectangle of the
/// local width and height, a custom section's section.contact_radius_m circle, or kNone.
ContactOutline contact_outline_at(const RodModel& model, double s_m, Side side = Side::kRight);

/// The gap of one section against one obstacle (the definition above).
struct SectionGap {
  double gap_m = 0.0;                                    ///< g; negative: penetration
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();   ///< n, direction of the force on the rod
  Eigen::Vector3d offset_W_m = Eigen::Vector3d::Zero();  ///< c, from p to the touching point
};

/// The contact candidates of one section against one obstacle, a fixed number per outline
/// kind (contact_candidate_count), each with its own gap, normal and touching point; a
/// solver gives each candidate its own multiplier lambda_j >= 0. Circle (and kNone, the
/// centerline itself, c = 0): one candidate, the support point of the definition above.
/// Rectangle: its 4 corners (exact point distances, g_j = d(p + c_j), n_j = grad d there),
/// so a face lying on a plane is held by its two corners' forces (any pressure across the
/// face has their statics), then for a curved obstacle (cylinder, sphere, box) the point of
/// each of its 4 edges nearest to the obstacle when it lies strictly inside the edge (a face
/// on a cylinder touches there), else (plane; nearest point at a corner) that candidate is
/// open with g = +infinity. Corners in the order (+x,+y), (-x,+y), (-x,-y), (+x,-y) of the
/// body frame, edges in the order from each corner to the next.
std::vector<SectionGap> section_gaps(const Obstacle& obstacle, const ContactOutline& outline,
                                     const Eigen::Vector3d& p_W_m, const Eigen::Matrix3d& R_WB);
/// Candidates per section: 1 for a circle or kNone, 8 for a rectangle.
int contact_candidate_count(ContactOutline::Kind kind);
/// The candidate of section_gaps with the smallest gap (the section's gap).
SectionGap section_gap(const Obstacle& obstacle, const ContactOutline& outline,
                       const Eigen::Vector3d& p_W_m, const Eigen::Matrix3d& R_WB);

// --- Results (both solvers; rod::Result::contacts) ---

/// One contiguous part of the body in contact with an obstacle.
struct ContactRegion {
  double s0_m = 0.0, s1_m = 0.0;                        ///< s0 = s1 for a point contact
  Eigen::Vector3d force_W_N = Eigen::Vector3d::Zero();  ///< resultant on the rod
};

/// What one obstacle does to the rod in a solution.
struct ContactResult {
  std::string obstacle;                                   ///< Obstacle::name
  Eigen::Vector3d force_W_N = Eigen::Vector3d::Zero();    ///< resultant on the rod (world)
  Eigen::Vector3d moment_W_Nm = Eigen::Vector3d::Zero();  ///< about the base point
  std::vector<ContactRegion> regions;  ///< in increasing s; empty when not touched
  double max_penetration_m = 0.0;      ///< max(0, -min g) over the points the solver checks
  /// Between those points (check_between_contact_points): how deep the section's core (its
  /// inscribed circle) goes into the obstacle along the centerline polyline [m], >= 0.
  double core_penetration_between_m = 0.0;
  double core_penetration_s_m = 0.0;  ///< where (the deepest point's s)
  bool in_contact() const { return !regions.empty(); }
};

/// A solver's contact force at one of its contact points (a grid node, an FE node or
/// quadrature point) against one obstacle.
struct ContactSample {
  double s_m = 0.0;
  Eigen::Vector3d point_W_m = Eigen::Vector3d::Zero();  ///< where it acts: p(s) + c
  Eigen::Vector3d force_W_N = Eigen::Vector3d::Zero();  ///< lambda n (zero where open)
  double gap_m = 0.0;
};

/// The result of one obstacle from a solver's samples (in increasing s): resultant, moment
/// about base_W_m, regions = maximal runs of consecutive samples with a non-zero force (a
/// lone sample is a point contact), max_penetration_m.
ContactResult summarize_contact(const Obstacle& obstacle, const std::vector<ContactSample>& samples,
                                const Eigen::Vector3d& base_W_m);

/// The solvers hold the rod off the obstacles at their contact points only (grid nodes, FE
/// nodes): between two of them it can pass into a curved obstacle smaller than their spacing.
/// Fills each contact's core_penetration_between_m from the result's centerline polyline (the
/// solver's contact points): per segment the point nearest the obstacle (exact on spheres and
/// cylinders; none on planes, where a chord lies above its ends), the depth of the section's
/// inscribed circle below the surface there. Where it exceeds half the inradius (the core half
/// inside: passed through, not the chord's sagitta on a wrapped obstacle) a converged result
/// becomes status "passes_between_contact_points" with a message naming the obstacle, the s and
/// the spacing needed. Results without obstacles or centerline are left alone.
void check_between_contact_points(const RodModel& model, Result& result);

/// Throws InputError unless the model's obstacles fit its reference configuration: no obstacle
/// contains the base point (naming obstacles[i] and the base), no section of the stress-free
/// shape penetrates an obstacle (naming obstacles[i] and the s, checked at every 1/1000 of
/// L, at every breakpoint and at both ends), and every section can touch (a custom section
/// needs section.contact_radius_m). RodModel readers call it after the body is known.
void check_obstacles(const RodModel& model);

}  // namespace tcasim::rod
