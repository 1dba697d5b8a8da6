#include "yaml_value_text.hpp"

namespace somasim::sweep {

std::string yaml_value_text(const YAML::Node& node) {
  // A plain scalar reads back as itself; yaml-cpp tags quoted scalars "!".
  if (node.IsScalar() && node.Tag() != "!" && node.Scalar().find('\n') == std::string::npos)
    return node.Scalar();
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  if (node.IsScalar())
    out << YAML::DoubleQuoted << node.Scalar();
  else
    out << node;
  return out.c_str();
}

}  // namespace somasim::sweep
