#include <algorithm>

#include "core/subdiv/refine.h"

namespace fb::subdiv {

uint32_t CornerSplitter::add(uint32_t vertex, const uint32_t* values, bool& fresh) {
  // Most vertices have one combination, seams a few: a short list per vertex.
  uint32_t* link = &first_[vertex];
  for (; *link != kNone; link = &next_[*link]) {
    // data(), not [], since a mesh without UV maps has no values at all (channels_ == 0).
    const uint32_t* known = values_of_.data() + size_t(*link) * channels_;
    if (std::equal(values, values + channels_, known)) {
      fresh = false;
      return *link;
    }
  }
  const uint32_t id = uint32_t(vertex_of_.size());
  *link = id;
  next_.push_back(kNone);
  vertex_of_.push_back(vertex);
  values_of_.insert(values_of_.end(), values, values + channels_);
  fresh = true;
  return id;
}

}  // namespace fb::subdiv
