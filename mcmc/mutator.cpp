#include "mcmc/mutator.h"

namespace dp::mcmc {

const char* proposal_status_name(ProposalStatus s) {
  switch (s) {
    case ProposalStatus::ok: return "ok";
    case ProposalStatus::no_choice: return "no_choice";
    case ProposalStatus::walk_ended: return "walk_ended";
    case ProposalStatus::light_not_found: return "light_not_found";
    case ProposalStatus::escaped: return "escaped";
    case ProposalStatus::occluded: return "occluded";
    case ProposalStatus::zero: return "zero";
    case ProposalStatus::off_image: return "off_image";
    case ProposalStatus::configuration: return "configuration";
    case ProposalStatus::chain_walk: return "chain_walk";
    case ProposalStatus::nonfinite: return "nonfinite";
    case ProposalStatus::count: break;
  }
  return "?";
}

}  // namespace dp::mcmc
