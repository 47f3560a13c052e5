// Members that differ from a finished run only in the faults' friction angles share that run when
// every fault sticks in it (docs/ensemble.md, "Friction variants of a run that sticks"). A stuck
// node pair holds its relative displacement whatever the friction: the contact equations of an
// all-stick run never read it, so a member with other angles has the same displacements,
// tractions and stresses, as long as its own chi stays below 1 at every pair and step. Only what
// ugs-solve evaluates with the friction changes: chi = |tau| / (c - sigma'_n tan(phi)) and the
// Coulomb stress change d|tau| + tan(phi) d sigma'_n, rewritten here in the fault tables; the
// other outputs are the run's (hard links).
#pragma once
#include <string>

#include "ugs/formats/case_file.hpp"

namespace ugs::ensemble {

// A case path setting a fault's friction angle: fault.<name>.friction_deg.
bool friction_only(const std::string& path);

struct FrictionVariant {
  bool derived = false;
  std::string reason;      // why not (derived = false), or what was checked (derived = true)
};

// Writes into `out_folder` the outputs of a run of `member` derived from the finished run in
// `run_folder` (its case `run`): the per-pair CSVs (*_fault_<F>.csv) and the fault table
// (*_faults.csv) with chi and the Coulomb stress change for the member's friction, every other
// output linked. Not derived (derived = false, `out_folder` to be discarded) when the run shows a
// pair slipping or open at some step, the per-pair CSVs lack a step of the fault table or do not
// start at the initial state (the Coulomb change 0), a safe-scale search ran (its answer depends
// on the friction), the member's chi reaches 1 somewhere, or a fault with cohesion changes its
// friction while showing interpolated pairs (their chi is a mean of their neighbours').
// InputError for unreadable or malformed outputs.
FrictionVariant derive_friction_variant(const std::string& run_folder, const CaseFile& run, const CaseFile& member,
                                        const std::string& out_folder);

}  // namespace ugs::ensemble
