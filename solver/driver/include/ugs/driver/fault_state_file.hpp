// The fault part of a faulted run's restart state: beside <state>.h5 (the volume, mech::write_state)
// the file <state stem>_faults.h5 holds the committed state of every node pair: a field series of
// one step on the fault surface of the fault outputs (one node per pair; tip nodes hold zeros) with
// node fields lambda (3, local frame [Pa]), g (3, local frame [m]), dp (fluid pressure change [Pa])
// and state (0 stick, 1 slip, 2 open). A restart reads both; their dates must agree.
#pragma once
#include <string>

#include "ugs/contact/contact.hpp"
#include "ugs/contact/fault_model.hpp"

namespace ugs::driver {

std::string fault_state_path(const std::string& state_h5);
void write_fault_state(const std::string& path, const contact::FaultModel& fm, const std::string& date, double time,
                       const contact::FaultContact::Snapshot& s);
// InputError if the file is missing, damaged, of another fault model, or of another date.
contact::FaultContact::Snapshot read_fault_state(const std::string& path, const contact::FaultModel& fm,
                                                 const std::string& date);

}  // namespace ugs::driver
