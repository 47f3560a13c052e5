// The part of a run that only a faulted mesh has (run.cpp): the fault model and its initial state
// against the Mohr-Coulomb limit, the fault contact coupled to the continuous solver, the fluid
// pressure change on the node pairs, the fault outputs and state of each step.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <mpi.h>

#include "ugs/contact/contact.hpp"
#include "ugs/contact/fault_model.hpp"
#include "ugs/contact/fault_output.hpp"
#include "ugs/mechanics/solver.hpp"

namespace ugs::driver {

using Log = std::function<void(int, const std::string&)>;

// Rank 0: the fault model of `mesh`, with a note per fault on its initial state.
contact::FaultModel build_faults(const Mesh& mesh, const CaseFile& cs, const mech::Model& model, const Log& note);

// Rank 0: the pressure change per node pair, the mean of its two sides' node values.
std::vector<double> pair_dp(const contact::FaultModel& fm, const std::vector<double>& node_dp);

// Rank 0: "max chi 0.512 (F), 3 node pairs slipping, 0 open" for the step's log line.
std::string fault_step_note(const contact::FaultModel& fm, const contact::FaultFields& ff);

}  // namespace ugs::driver
