#include "profile_json.h"

namespace drape::app {

nlohmann::json profileJson(const PhaseProfile& p) {
  return {{"assembly_s", p.assembly},       {"linear_solve_s", p.linearSolve}, {"contact_queries_s", p.contactQueries},
          {"line_search_s", p.lineSearch}, {"bookkeeping_s", p.bookkeeping}, {"steps_s", p.total()}};
}

}  // namespace drape::app
