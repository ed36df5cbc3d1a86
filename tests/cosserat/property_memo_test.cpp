// The shooting right-hand side's memo of a varying body's properties along s
// (RodRhs::LocalMemo): what local(s) returns from it must be the model's values bit for bit,
// on the side of s inside the current piece, with the homotopy in omega* applied as
// RodProblem::properties applies it; and the memo keeps each (s, side) apart up to its
// capacity.
#include <gtest/gtest.h>

#include <vector>

#include "cosserat/internal/layout.hpp"
#include "cosserat/internal/rhs.hpp"
#include "rod/scenario.hpp"
#include "support/varying_body.hpp"

namespace tcasim::cosserat::internal {
namespace {

/// Bit-for-bit equality of two Locals (each component compared with ==).
void expect_same(const RodRhs::Local& a, const RodRhs::Local& b, double s) {
  EXPECT_TRUE(a.Kn == b.Kn && a.Kw == b.Kw && a.Kn_inv == b.Kn_inv && a.Kw_inv == b.Kw_inv &&
              a.ws == b.ws && a.wf == b.wf && a.dKn == b.dKn && a.dKw == b.dKw && a.dws == b.dws)
      << "s = " << s;
}

/// A Local whose every component encodes (i, side), to tell entries apart.
RodRhs::Local tagged(int i, rod::Side side) {
  const double v = 2.0 * i + (side == rod::Side::kLeft ? 1.0 : 0.0);
  RodRhs::Local k;
  k.Kn = k.Kw = k.Kn_inv = k.Kw_inv = k.ws = k.dKn = k.dKw = k.dws = Vec3::Constant(v);
  k.wf = v;
  return k;
}

TEST(PropertyMemo, KeepsEachPointAndSideApartUpToItsCapacity) {
  RodRhs::LocalMemo memo;
  constexpr int kPoints = 3000;  // 6000 entries with both sides: beyond the 4096 stored
  std::vector<double> s(kPoints);
  for (int i = 0; i < kPoints; ++i) s[i] = 0.2 * i / (kPoints - 1);  // a grid on [0, L]
  EXPECT_EQ(memo.find(s[0], rod::Side::kRight), nullptr);
  int stored = 0;
  for (int i = 0; i < kPoints; ++i) {
    for (const rod::Side side : {rod::Side::kRight, rod::Side::kLeft}) {
      const RodRhs::Local k = tagged(i, side);
      expect_same(memo.insert(s[i], side, k), k, s[i]);  // also once full
      if (memo.size() > static_cast<std::size_t>(stored)) ++stored;
    }
  }
  EXPECT_EQ(stored, 4096);
  int found = 0;
  for (int i = 0; i < kPoints; ++i) {
    for (const rod::Side side : {rod::Side::kRight, rod::Side::kLeft}) {
      const RodRhs::Local* k = memo.find(s[i], side);
      if (k == nullptr) continue;
      expect_same(*k, tagged(i, side), s[i]);
      ++found;
    }
  }
  EXPECT_EQ(found, stored);  // the first 4096 inserted, each under its own key
  EXPECT_EQ(memo.find(0.1 + 1e-17, rod::Side::kRight), nullptr);
  EXPECT_EQ(memo.find(-1.0, rod::Side::kLeft), nullptr);

  // One side only, the table half full (long probe runs): the other side is never found.
  RodRhs::LocalMemo right_only;
  for (int i = 0; i < 2048; ++i) {
    right_only.insert(s[i], rod::Side::kRight, tagged(i, rod::Side::kRight));
  }
  int left_found = 0;
  for (int i = 0; i < 2048; ++i) left_found += right_only.find(s[i], rod::Side::kLeft) != nullptr;
  EXPECT_EQ(left_found, 0);
}

/// Checks local(s) against the model's values on a grid of every piece (knots included, each
/// from the side inside the piece), once filling the memo and once reading it.
void expect_local_is_the_models(const rod::RodModel& m) {
  RodRhs rhs(m, make_3d_layout(), false);
  ASSERT_FALSE(rhs.knots.empty());
  constexpr int kIntervals = 8;
  for (const int pass : {0, 1}) {
    const std::size_t size_before = rhs.memo.size();
    for (std::size_t p = 0; p + 1 < rhs.knots.size(); ++p) {
      const double lo = rhs.knots[p], hi = rhs.knots[p + 1];
      rhs.pieces.enter(lo, hi);
      for (int j = 0; j <= kIntervals; ++j) {
        const double s = j == kIntervals ? hi : lo + (hi - lo) * j / kIntervals;
        const rod::Side side = j < kIntervals / 2 ? rod::Side::kRight : rod::Side::kLeft;
        expect_same(rhs.local(s), rhs.model_local(s, side), s);
        // The homotopy in omega*: local() applies mu to omega* and its slope as
        // RodProblem::properties does.
        rhs.set_omega_star_fraction(0.25);
        Vec3 Kn, Kw, ws;
        double wf = 0.0;
        rhs.properties(s, side, Kn, Kw, ws, wf);
        RodRhs::Local expected = rhs.model_local(s, side);
        expected.ws = ws;
        expected.dws *= 0.25;
        expect_same(rhs.local(s), expected, s);
        rhs.set_omega_star_fraction(1.0);
      }
    }
    if (pass == 0) {
      EXPECT_GT(rhs.memo.size(), size_before);
    } else {
      EXPECT_EQ(rhs.memo.size(), size_before);  // every point found
    }
  }
}

TEST(PropertyMemo, LocalOfTheTaperedTentacleIsTheModelsValuesBitForBit) {
  expect_local_is_the_models(rod::parse_scenario(test_support::hanging_tentacle(true)));
}

TEST(PropertyMemo, LocalOfTheSteppedPrecurvedBodyIsTheModelsValuesBitForBit) {
  expect_local_is_the_models(rod::parse_scenario(test_support::loaded_varying_body()));
}

}  // namespace
}  // namespace tcasim::cosserat::internal
