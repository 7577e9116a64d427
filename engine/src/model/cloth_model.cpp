#include "drape/model/cloth_model.h"

#include <cmath>
#include <sstream>

#include "drape/core/input_error.h"

namespace drape::model {

void validateStitches(const ClothModel& model, const std::string& context) {
  const int nv = model.numVertices();
  auto inRange = [nv](int v) { return v >= 0 && v < nv; };
  for (size_t s = 0; s < model.stitches.size(); ++s) {
    const auto [a, b] = model.stitches[s];
    if (!inRange(a) || !inRange(b))
      throw InputError(context + ": stitch " + std::to_string(s) + ": vertices (" + std::to_string(a) + ", " +
                       std::to_string(b) + ") invalid (" + std::to_string(nv) + " vertices)");
  }
  for (size_t s = 0; s < model.edgeStitches.size(); ++s) {
    const EdgeStitch& e = model.edgeStitches[s];
    const std::string where = context + ": edge stitch " + std::to_string(s) + ": ";
    for (const auto& [name, v] :
         {std::pair<const char*, int>{"vertex", e.vertex}, {"edge end a", e.a}, {"edge end b", e.b}})
      if (!inRange(v))
        throw InputError(where + name + " " + std::to_string(v) + " out of range (" + std::to_string(nv) +
                         " vertices)");
    if (e.a == e.b)
      throw InputError(where + "edge (" + std::to_string(e.a) + ", " + std::to_string(e.b) + ") is degenerate");
    if (e.vertex == e.a || e.vertex == e.b)
      throw InputError(where + "vertex " + std::to_string(e.vertex) + " is an end of its own edge (" +
                       std::to_string(e.a) + ", " + std::to_string(e.b) + ")");
    if (!(e.t >= 0.0 && e.t <= 1.0)) {
      std::ostringstream os;
      os << where << "t = " << e.t << " outside [0, 1]";
      throw InputError(os.str());
    }
  }
}

}  // namespace drape::model
