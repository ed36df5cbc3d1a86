#pragma once
/// The physics-based TCA model of [Pawlowski2019] Section II, Eqs. (1)-(6), with the
/// decisions of docs/conventions.md (corrected lengths, selectable f12 factor, current
/// fiber diameter, chirality sign, closed coils).
///
/// Units: SI inside (m, N, Pa, K). Temperatures are absolute [K]; material laws
/// are written in degC in their data files and converted when evaluated.
/// Sign conventions: the tension F > 0 pulls the TCA longer; the elongation
/// delta > 0 lengthens it (delta = 0 at the coiled length L).
#include <optional>
#include <string>
#include <vector>

namespace tcasim::tca {

/// Extension (heterochiral: twist and coil of opposite hand) or contraction (homochiral).
enum class Kind { kExtension, kContraction };

/// Factor in Eq. (4): `kPaper` prints 8; `kCastigliano` is the consistent 16.
enum class F12Form { kPaper, kCastigliano };

const char* to_string(Kind k);
const char* to_string(F12Form f);

/// p(T) = c0 + c1 T + c2 T^2 + ... with T in degC (a constant is a degree-0 polynomial).
struct PolynomialDegC {
  std::vector<double> coefficients;
  /// Value at absolute temperature t_K.
  double value(double t_K) const;
  /// d p / d T [1/K] at absolute temperature t_K.
  double derivative(double t_K) const;
};

/// Fiber diameter ratio d(T)/d0.
struct DiameterLaw {
  enum class Type { kLinearExpansion, kRatioPolynomial };
  Type type = Type::kLinearExpansion;
  /// Linear expansion coefficient rho [1/K]: d/d0 = 1 + rho (T - T_ref).
  double linear_expansion_1_K = 0.0;
  /// Ratio polynomial: d/d0 = p(T)/p(T_ref).
  PolynomialDegC ratio_polynomial;
};

/// Material properties at one temperature with their temperature derivatives.
struct MaterialState {
  double youngs_modulus_Pa;  ///< E_T
  double shear_modulus_Pa;   ///< G_T
  double diameter_ratio;     ///< d(T)/d0
  double dE_dT_Pa_K;         ///< dE_T/dT
  double dG_dT_Pa_K;         ///< dG_T/dT
  double dratio_dT_1_K;      ///< d(d/d0)/dT
};

/// Temperature-dependent properties of a twisted fiber (data, with its source named).
struct Material {
  std::string name;                         ///< id (file stem for shipped materials)
  std::string source;                       ///< where the numbers come from
  double reference_temperature_K = 298.15;  ///< T_ref, at which d = d0
  PolynomialDegC youngs_modulus_Pa;         ///< E_T(T)
  PolynomialDegC shear_modulus_Pa;          ///< G_T(T)
  DiameterLaw diameter;
  /// The Eq. (4) factor the moduli were identified with, if the source states one.
  std::optional<F12Form> f12_form;
  /// Temperature range over which the law is valid [K].
  double min_temperature_K = 0.0;
  double max_temperature_K = 1e9;

  /// Evaluates the laws at t_K. Throws DomainError outside the valid range or where
  /// a modulus or the diameter ratio is not positive.
  MaterialState at(double t_K) const;
};

/// Measurable parameters of one TCA, as in [Pawlowski2019] Section II.
struct Parameters {
  Kind kind = Kind::kExtension;
  double coiled_length_m = 0.0;   ///< L, the closed coiled length
  double fiber_length_m = 0.0;    ///< l, the twisted fiber length (l > L)
  double outer_diameter_m = 0.0;  ///< D
  double twist_turns = 0.0;       ///< N, inserted twist turns
  F12Form f12_form = F12Form::kCastigliano;
  /// d0 [m], the measured fiber diameter at the material's reference temperature. Absent (the
  /// default): the paper's closed-coil d0 = 2 D L/l and n = 2 cos(alpha0) l/(pi D). Given: the
  /// helix of mean diameter D - d0 (docs/conventions.md "Measured fiber diameter").
  std::optional<double> fiber_diameter_m;
};

/// Relative disagreement allowed between over-determined geometry values (measured values
/// quoted to three digits round by up to 0.5 %), and the tolerance of the closed-length check
/// n d0 <= L for a coil wound closed.
inline constexpr double kGeometryRelativeTolerance = 0.01;

/// Helix of mean diameter Dm = D - d0 with n coils over the coiled length L: each coil is one
/// turn of fiber, l^2 = (pi Dm n)^2 + L^2. Returns l [m].
double fiber_length_from_coil_count(double coiled_length_m, double mean_diameter_m,
                                    double coil_count);

/// The same helix from its pitch angle: tan(alpha0) = L/(pi Dm n). Returns n.
double coil_count_from_pitch(double coiled_length_m, double mean_diameter_m,
                             double pitch_angle_rad);

/// Fiber length from the coiled length and the initial pitch angle: l = L / sin(alpha0).
double fiber_length_from_pitch(double coiled_length_m, double pitch_angle_rad);

/// Coefficients of Eq. (2) at one pitch angle and temperature.
struct Coefficients {
  double f11_m_N;  ///< f11 [m/N], Eq. (3)
  double f12_1_N;  ///< f12 [1/N], Eq. (4) with the chosen factor
  double tau_Nm;   ///< tau [N m], Eq. (1)
};

/// Value and consistent tangents of the tension law F(delta, T).
struct TensionState {
  double tension_N;        ///< F
  double dF_ddelta_N_m;    ///< dF/d delta
  double dF_dT_N_K;        ///< dF/dT
  double pitch_angle_rad;  ///< alpha at this elongation, Eq. (5)
  /// True for a TCA with coil contact pushed below its closed length (delta < delta_c): the
  /// free-coil law is then an extrapolation; physically the coils are in contact.
  bool below_closed_length;
};

/// Result of the elongation law delta(F, T).
struct ElongationState {
  double elongation_m;     ///< delta
  double pitch_angle_rad;  ///< alpha
  bool coils_closed;       ///< held at its closed length delta_c by coil contact
};

/// One TCA: the measurable parameters converted to model constants, and its material.
class Tca {
 public:
  /// Validates the parameters (throws InputError naming the parameter) and converts:
  /// alpha0 = asin(L/l), phi0 = 2 pi N, and
  /// - without fiber_diameter_m: n = 2 cos(alpha0) l/(pi D), d0 = 2 D L/l ([Pawlowski2019]);
  /// - with it: d0 given, n = l cos(alpha0)/(pi (D - d0)), refusing d0 >= D/2 (fiber thicker
  ///   than the coil), n d0 > L (overlapping coils) and l/N < d0 (a twist pitch shorter than
  ///   the fiber is thick).
  Tca(const Parameters& parameters, Material material);

  const Parameters& parameters() const { return p_; }
  const Material& material() const { return material_; }
  double initial_pitch_angle_rad() const { return alpha0_; }  ///< alpha0
  double coil_count() const { return n_; }                    ///< n
  double initial_twist_rad() const { return phi0_; }          ///< phi0
  double initial_fiber_diameter_m() const { return d0_; }     ///< d0
  /// +1 for extension, -1 for contraction: delta = f11 F + s f12 tau.
  double chirality() const;
  /// True when d0 is the measured fiber_diameter_m, false for the paper's d0 = 2 D L/l.
  bool has_measured_fiber_diameter() const { return p_.fiber_diameter_m.has_value(); }
  /// Dm [m], the coil's mean diameter: D - d0 with a measured d0; D/2 for the paper's
  /// conversions (the diameter their n implies, docs/conventions.md).
  double mean_coil_diameter_m() const;
  /// delta_c [m], the elongation at the closed length, where the coils touch: 0 for the
  /// paper's TCAs (made closed); n d0 - L (<= 0) with a measured d0 (0 when wound closed).
  /// Meaningful where has_coil_contact(); for the paper's contraction TCA it is -L (a flat
  /// coil, the end of the domain of Eq. (5)).
  double closed_elongation_m() const { return closed_elongation_; }

  /// f11, f12 and tau at pitch angle alpha and temperature t_K.
  Coefficients coefficients(double alpha_rad, double t_K) const;

  /// Eq. (5): alpha from the elongation; throws DomainError if sin(alpha) leaves (0, 1).
  double pitch_angle(double elongation_m) const;

  /// Eq. (6): the tension at a given elongation and temperature (free-coil law), with
  /// its consistent tangents.
  TensionState tension(double elongation_m, double t_K) const;

  /// Eqs. (2)+(5): the elongation under tension F at temperature t_K (bracketed root
  /// finding in alpha). A TCA with coil contact cannot shorten below its closed length:
  /// when the free solution has delta < delta_c the result is delta_c, coils_closed.
  /// The paper's contraction TCA has no such limit: its coils are assumed open (prestretched),
  /// so delta < 0 (shorter than L) is returned as computed.
  ElongationState elongation(double tension_N, double t_K) const;

  /// Eqs. (2)+(5) without coil contact: the free-coil elongation (may be negative for an
  /// extension TCA; then it is below its closed length). Throws DomainError naming the
  /// searched pitch-angle bracket if no solution exists.
  ElongationState free_coil_elongation(double tension_N, double t_K) const;

  /// Temperature at which the tension at `elongation_m` equals `tension_N`, searched in
  /// [t_lo_K, t_hi_K]; throws DomainError naming the range if none lies there.
  double temperature_for_tension(double tension_N, double elongation_m, double t_lo_K,
                                 double t_hi_K) const;

  /// Onset temperature of a TCA with coil contact under tension F (F < 0 compresses it): the
  /// lowest temperature in [t_lo_K, t_hi_K] at which the coils open (delta leaves delta_c).
  /// Returns nullopt if they stay closed over the whole range.
  std::optional<double> onset_temperature(double tension_N, double t_lo_K, double t_hi_K) const;

  /// Free stroke: the elongation at zero tension.
  double free_stroke(double t_K) const { return elongation(0.0, t_K).elongation_m; }

  /// Blocked force: the tension with the TCA held at its coiled length L (delta = 0).
  double blocked_force(double t_K) const { return tension(0.0, t_K).tension_N; }

  /// F_c(T) [N]: the free-coil tension at the closed length (delta = delta_c); the blocked
  /// force for the paper's TCAs. Segments are closed while the tension is below it.
  double closed_force(double t_K) const { return tension(closed_elongation_, t_K).tension_N; }

  /// True when coil contact bounds this TCA at its closed length (delta >= delta_c): extension
  /// TCAs, and every TCA with a measured fiber diameter. The paper's contraction TCA is
  /// modelled with open coils at L (docs/conventions.md "Closed coils"): it is bounded only by
  /// the domain of Eq. (5), 0 < alpha < 90 deg.
  bool has_coil_contact() const {
    return p_.kind == Kind::kExtension || p_.fiber_diameter_m.has_value();
  }

  /// k_c [N/m]: |dF/d delta| at delta = 0 and the material's reference temperature (clamped
  /// to its valid range). Scales the closed-coil branch of contact_residual to force units.
  double contact_stiffness_N_m() const { return contact_stiffness_; }

 private:
  Parameters p_;
  Material material_;
  double alpha0_ = 0, n_ = 0, phi0_ = 0, d0_ = 0;
  double closed_elongation_ = 0;
  double contact_stiffness_ = 0;
};

/// One segment of a TCA driven at its own temperature (segments in series, base to tip).
struct Segment {
  double fraction;       ///< share of the TCA's length, (0, 1], summing to 1
  double temperature_K;  ///< segment temperature
};

/// Value and tangents of the series law F(delta_total, T_1..T_k).
struct SeriesTensionState {
  double tension_N;
  double dF_ddelta_N_m;
  std::vector<double> dF_dT_N_K;  ///< one per segment
};

/// Total elongation of segments in series under one shared tension:
/// delta = sum_k f_k delta(F, T_k) (a fraction f of a TCA scales f11, f12 and n by f).
double series_elongation(const Tca& tca, double tension_N, const std::vector<Segment>& segments);

/// Shared tension of segments in series whose total elongation is delta (free-coil
/// law in each segment), with consistent tangents. Bracketed root finding in F.
SeriesTensionState series_tension(const Tca& tca, double elongation_m,
                                  const std::vector<Segment>& segments);

/// The TCA law with coil contact as one equation between the shared tension F of the
/// string and its total elongation delta (docs/conventions.md "Closed coils"). In each
/// segment k (fraction f_k) of a TCA with coil contact, with its closed elongation
/// delta_c (0 for the paper's extension TCA, n d0 - L with a measured d0):
/// delta_k >= f_k delta_c, contact force c_k >= 0, c_k (delta_k - f_k delta_c) = 0 and
/// F = F_free(delta_k / f_k, T_k) - c_k. Eliminating delta_k and c_k, phi(F, delta) = 0 holds
/// exactly at those states:
///   one segment:   phi = max(F - F_free(delta, T), -k_c (delta - delta_c))   (the min
///                  complementarity function of (k_c (delta - delta_c), c) with c = F_free - F;
///                  for delta < delta_c, where no free-coil state exists, F_free is continued
///                  as F_c(T) + k_c (delta - delta_c));
///   k > 1 segments: phi = k_c (sum_k f_k max(delta_c, e(F, T_k)) - delta), e the free-coil
///                  elongation (Eqs. (2), (5)); the max is absent without coil contact.
/// phi is piecewise smooth (semismooth), so Newton with these derivatives converges
/// quadratically; in force units [N]. One open segment gives phi = F - F_free(delta, T), the
/// free-coil row of both rod solvers.
struct ContactResidual {
  double phi_N;            ///< phi(F, delta)
  double dphi_dF;          ///< d phi / d F (1 for an open single segment, 0 when closed)
  double dphi_ddelta_N_m;  ///< d phi / d delta
  double dphi_dT_N_K;      ///< d phi / d T for one shift of every segment temperature
};

/// phi(F, delta) and its derivatives (see ContactResidual). Throws DomainError where the
/// free-coil law has no state (pitch angle outside (0, 90 deg), temperature out of range).
ContactResidual contact_residual(const Tca& tca, double tension_N, double elongation_m,
                                 const std::vector<Segment>& segments);

/// Coil contact of one segment in a solved state.
struct SegmentContact {
  bool coils_closed = false;     ///< the segment sits at its closed length, F < F_c(T_k)
  double contact_force_N = 0.0;  ///< c_k = F_c(T_k) - F >= 0 when closed, else 0
};

/// The contact state of each segment at the shared tension F (TCAs with coil contact; the
/// paper's contraction TCA's segments are always open). F_c is Tca::closed_force.
std::vector<SegmentContact> segment_contacts(const Tca& tca, double tension_N,
                                             const std::vector<Segment>& segments);

}  // namespace tcasim::tca
