#pragma once
/// tcasim: kinetostatics of soft robots actuated by twisted-and-coiled actuators.
/// The umbrella header of the installed package (`#include <tcasim/tcasim.hpp>`, target
/// tcasim::tcasim): every component's interface.
///  - common: errors (InputError, DomainError), units, SO(3), ODE integrators, data folders;
///  - tca: the TCA model and its calibration;
///  - rod: rod models, scenario files, results;
///  - cosserat: the Cosserat-rod shooting solver, inverse kinetostatics and grasps;
///  - beam_fe: the geometrically exact beam finite-element solver;
///  - method: either method by its options' type, with one call shape (static and dynamic);
///  - crosscheck: cross-checks of the two solvers and FE convergence studies;
///  - study: sweeps of one actuator with either solver, in cold-started chunks.
#include "beam_fe/beam_fe.hpp"
#include "common/data_dir.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "cosserat/inverse.hpp"
#include "cosserat/shooting.hpp"
#include "crosscheck/crosscheck.hpp"
#include "method/dynamics.hpp"
#include "method/method.hpp"
#include "rod/model.hpp"
#include "rod/result.hpp"
#include "rod/scenario.hpp"
#include "study/sweep.hpp"
#include "tca/calibration.hpp"
#include "tca/tca.hpp"
