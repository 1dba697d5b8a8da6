#include "landscape_figure.hpp"
namespace somasim::plugins {
void draw_landscapes(NodeContext&, pps::BodyPartLearner&, const std::vector<double>&,
                     const std::string&) {}
}  // namespace somasim::plugins
