#include "gl/gpu_timeline.h"

#include <epoxy/gl.h>

namespace luxel::gl {

GpuTimeline::~GpuTimeline() {
  std::vector<unsigned> all = free_;
  for (const Open& o : open_) {
    all.push_back(o.begin);
    if (o.end) all.push_back(o.end);
  }
  if (!all.empty()) glDeleteQueries(GLsizei(all.size()), all.data());
}

unsigned GpuTimeline::query() {
  GLuint q = 0;
  if (!free_.empty()) {
    q = free_.back();
    free_.pop_back();
  } else {
    glCreateQueries(GL_TIMESTAMP, 1, &q);
  }
  glQueryCounter(q, GL_TIMESTAMP);
  return q;
}

void GpuTimeline::mark(const char* phase) {
  stop();
  open_.push_back({phase, query(), 0u, clock_.seconds(), 0.0});
  running_ = true;
}

void GpuTimeline::stop() {
  if (!running_) return;
  Open& o = open_.back();
  o.end = query();
  o.cpuEnd = clock_.seconds();
  running_ = false;
}

PhaseTime& GpuTimeline::total(const char* phase) {
  for (PhaseTime& t : totals_)
    if (t.name == phase) return t;
  totals_.push_back({phase, 0, 0.0, 0.0});
  return totals_.back();
}

void GpuTimeline::collect() {
  const size_t finished = open_.size() - (running_ ? 1 : 0);
  for (size_t i = 0; i < finished; ++i) {
    const Open& o = open_[i];
    GLuint64 begin = 0, end = 0;
    glGetQueryObjectui64v(o.begin, GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(o.end, GL_QUERY_RESULT, &end);
    PhaseTime& t = total(o.phase);
    ++t.count;
    t.secondsGpu += end > begin ? double(end - begin) * 1e-9 : 0.0;
    t.secondsCpu += o.cpuEnd - o.cpuBegin;
    free_.push_back(o.begin), free_.push_back(o.end);
  }
  open_.erase(open_.begin(), open_.begin() + ptrdiff_t(finished));
}

}  // namespace luxel::gl
