#include "somasim/pps/learned_state.hpp"

#include <utility>

namespace somasim::pps {

LearnedState learned_state(const BodyPartLearner& learner) {
  LearnedState s;
  s.body_part = learner.body_part();
  s.model = learner.params().model;
  s.grid = learner.map_grid();
  s.parzen = learner.params().parzen;
  s.taxels.reserve(learner.taxels().size());
  for (std::size_t k = 0; k < learner.taxels().size(); ++k)
    s.taxels.push_back(LearnedTaxel{learner.taxels()[k].id, learner.taxels()[k].pose_link,
                                    learner.maps()[k].pos(), learner.maps()[k].neg(),
                                    learner.contact_d_sum(static_cast<int>(k)),
                                    learner.contact_count(static_cast<int>(k))});
  return s;
}

TaxelMap make_map(const LearnedState& state, const LearnedTaxel& taxel) {
  return TaxelMap(state.grid, state.parzen, taxel.pos, taxel.neg);
}

BodyPartLearner make_learner(const LearnedState& state, LearnerParams params) {
  params.model = state.model;
  params.grid = state.grid;
  params.parzen = state.parzen;
  std::vector<TaxelInfo> infos;
  infos.reserve(state.taxels.size());
  for (const LearnedTaxel& t : state.taxels) infos.push_back(TaxelInfo{t.id, t.pose_link});
  BodyPartLearner learner(state.body_part, std::move(infos), params);
  for (std::size_t k = 0; k < state.taxels.size(); ++k) {
    learner.maps()[k] = make_map(state, state.taxels[k]);
    learner.set_contact_offset(static_cast<int>(k), state.taxels[k].contact_d_sum,
                               state.taxels[k].contact_events);
  }
  return learner;
}

}  // namespace somasim::pps
