#pragma once
/// Shape output of a solved rod: the deformed centerline and every actuator's string path,
/// as VTK XML PolyData (.vtp, ASCII, for ParaView) or as a CSV table (for matplotlib).
///
/// Curves: the centerline p_W(s) first, then one path per actuator in model order,
///   q_i(s) = p_W(s) + R_WB(s) r_i,B(s)
/// at the result's centerline samples (r_i,B: the actuator's routing in the body frame).
/// An actuator with `count` parallel strings has all of them at the same place: one path.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rod/model.hpp"
#include "rod/result.hpp"

namespace tcasim::rod {

/// One polyline of a shape.
struct ShapeCurve {
  std::string name;         ///< "centerline" or the actuator's name
  int actuator_id;          ///< -1 for the centerline, else the actuator's index in the model
  std::vector<double> s_m;  ///< reference arc length at each point [m]
  std::vector<Eigen::Vector3d> p_W_m;  ///< point in the world frame [m]
};

/// The centerline and the actuator paths of `result` (sampled at its centerline samples).
/// Throws std::invalid_argument when the result's centerline arrays differ in length, and
/// DomainError when a sample is not finite.
std::vector<ShapeCurve> shape_curves(const RodModel& model, const Result& result);

/// The .vtp document: one VTK XML PolyData piece with one polyline per curve; point data
/// `s_m` (Float64) and `actuator_id` (Int32, -1 = centerline), cell data `actuator_id`,
/// field data `scenario`, `method` and `curve_names` (String arrays).
std::string vtp_document(const RodModel& model, const Result& result);

/// Writes vtp_document(model, result) to `path` (InputError "vtk file" when it cannot be
/// written); with obstacles also obstacles_vtp_document to obstacles_vtp_path(path).
void write_vtp(const RodModel& model, const Result& result, const std::string& path);

/// The model's obstacles as surfaces (VTK XML PolyData, polygons; cell data `obstacle_id`,
/// field data `obstacle_names`), so ParaView shows the rod with what it touches: spheres and
/// boxes whole, planes and cylinders (unbounded) as the patch around the result's centerline
/// (its bounding box grown by half the rod length each way). Empty string without obstacles.
std::string obstacles_vtp_document(const RodModel& model, const Result& result);
/// Where write_vtp puts the obstacles: `path` with its `.vtp` ending (if any) replaced by
/// `.obstacles.vtp`.
std::string obstacles_vtp_path(const std::string& path);

/// The shape CSV: header `curve,actuator_id,s_m,x_m,y_m,z_m`, one row per point, curves in
/// the order of shape_curves().
std::string shape_csv_document(const RodModel& model, const Result& result);

/// Writes shape_csv_document(model, result) to `path` (InputError "shape csv file" on failure).
void write_shape_csv(const RodModel& model, const Result& result, const std::string& path);

}  // namespace tcasim::rod
