#pragma once
// The derivative check of the TCA contact residual (tca::contact_residual) shared by the tca
// tests: each analytic derivative against central differences on a list of cases.
#include <gtest/gtest.h>

#include <vector>

#include "tca/tca.hpp"

namespace tcasim::tca::testing {

/// One point of the contact residual: tension, elongation and segments.
struct ContactCase {
  const char* what;
  double tension_N, elongation_m;
  std::vector<Segment> segs;
};

/// Expects dphi/dF, dphi/ddelta and dphi/dT of contact_residual at every case to match central
/// differences (steps 1e-7 N, 1e-9 m, 1e-3 K) within rel_tol times their scales: 1 (per N), the
/// contact stiffness k_c (per m) and k_c x 1e-4 m/K (per K).
inline void expect_contact_residual_derivatives(const Tca& tca,
                                                const std::vector<ContactCase>& cases,
                                                double rel_tol) {
  const auto central = [](const auto& f, double x, double h) {
    return (f(x + h) - f(x - h)) / (2.0 * h);
  };
  const double kc = tca.contact_stiffness_N_m();
  for (const ContactCase& c : cases) {
    SCOPED_TRACE(c.what);
    const ContactResidual r = contact_residual(tca, c.tension_N, c.elongation_m, c.segs);
    const auto phi_F = [&](double F) {
      return contact_residual(tca, F, c.elongation_m, c.segs).phi_N;
    };
    const auto phi_d = [&](double d) {
      return contact_residual(tca, c.tension_N, d, c.segs).phi_N;
    };
    const auto phi_T = [&](double dT) {
      std::vector<Segment> s = c.segs;
      for (Segment& k : s) k.temperature_K += dT;
      return contact_residual(tca, c.tension_N, c.elongation_m, s).phi_N;
    };
    EXPECT_NEAR(r.dphi_dF, central(phi_F, c.tension_N, 1e-7), rel_tol);
    EXPECT_NEAR(r.dphi_ddelta_N_m, central(phi_d, c.elongation_m, 1e-9), rel_tol * kc);
    EXPECT_NEAR(r.dphi_dT_N_K, central(phi_T, 0.0, 1e-3), rel_tol * kc * 1e-4);
  }
}

}  // namespace tcasim::tca::testing
