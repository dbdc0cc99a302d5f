// SPDX-License-Identifier: MIT
#include <curvestep/host/link/wire.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include <curvestep/core/error_text.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/firmware/conversions.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/joint_stops.hpp>

namespace curvestep::host::link {
namespace {

constexpr double two_pi = 6.283185307179586476925286766559;

std::uint32_t to_whole(double value, bool& exact) {
  const double rounded = std::nearbyint(value);
  if (!(rounded >= 0 && rounded <= 4294967295.0)) throw std::out_of_range("value outside 0 .. 2^32-1");
  if (rounded != value) exact = false;
  return static_cast<std::uint32_t>(rounded);
}

/// The extra full turns of an arc: its sweep minus the sweep of the same arc without extra turns
/// (as the controller will rebuild it from the wire points), in whole turns.
std::uint32_t extra_turns(const PathSegment& s, const protocol::QueueSegment& q, const std::string& where) {
  const auto point = [&q](std::size_t slot, std::size_t axes) {
    MachinePoint p{};
    for (std::size_t a = 0; a < axes && a < motion_axes; ++a) p[a] = static_cast<double>(q.points[slot][a]) / 65536.0;
    return p;
  };
  // Only the sweep matters here, so any radius difference is accepted (the controller checks it).
  const auto base = PathSegment::make_arc(point(0, q.axis_count), point(1, q.axis_count), point(2, 2), q.direction, 0,
                                          std::numeric_limits<double>::max());
  if (!base) throw std::runtime_error(where + "the arc cannot be rebuilt from its wire points");
  const double turns = std::nearbyint((std::fabs(s.arc_sweep_rad()) - std::fabs(base.value().arc_sweep_rad())) / two_pi);
  if (!(turns >= 0 && turns <= 4294967295.0)) throw std::runtime_error(where + "the arc's number of turns is out of range");
  return static_cast<std::uint32_t>(turns);
}

/// The file segment index of the job's segment `i` (Job::source_index, or `i` without one).
std::size_t file_segment(const Job& job, std::size_t i) { return job.source_index.empty() ? i : job.source_index[i]; }

}  // namespace

std::int32_t to_q16(double value, bool& exact) {
  // The one rounding of every host path (docs/protocol.md, "Conventions"): Q16_16::from_double,
  // to nearest with ties away from zero, as the job loaders quantise coordinates.
  const auto fixed = Q16_16::from_double(value);
  if (!fixed) throw std::out_of_range("value " + format_number(value) + " outside the Q16.16 range");
  if (static_cast<double>(fixed.value().raw()) != value * 65536.0) exact = false;
  return fixed.value().raw();
}

WireMachine to_wire(const MachineLimits& m, std::size_t axis_count) {
  WireMachine out;
  auto& c = out.configuration;
  const auto q16 = [&out](double value, const char* field) {
    bool exact = true;
    const std::int32_t raw = to_q16(value, exact);
    if (!exact) {
      out.notes.push_back(std::string(field) + " " + format_number(value) + " travels as " +
                          format_number(static_cast<double>(raw) / 65536.0) + " (Q16.16)");
    }
    return raw;
  };
  const auto whole = [&out](double value, const char* field) {
    bool exact = true;
    const std::uint32_t v = to_whole(value, exact);
    if (!exact) out.notes.push_back(std::string(field) + " " + format_number(value) + " travels as " + std::to_string(v));
    return v;
  };
  // Planning limits travel as binary64, exactly; feeds (the default and the rapid speed) as
  // Q16.16 like segment feeds, and the rate as a whole number.
  c.axis_count = static_cast<std::uint8_t>(axis_count);
  c.profile = m.jerk_limited ? protocol::ProfileKind::SCurve : protocol::ProfileKind::Trapezoid;
  c.max_velocity_mm_per_s = m.v_max_mm_per_s;
  c.max_acceleration_mm_per_s2 = m.a_max_mm_per_s2;
  c.max_jerk_mm_per_s3 = m.j_max_mm_per_s3;
  c.tolerance_mm = m.tolerance_mm;
  c.junction_deviation_mm = m.junction_deviation_mm;
  c.max_step_rate_hz = m.max_step_rate_hz;
  c.default_feed_mm_per_s = q16(m.feed_mm_per_s, "feed");
  c.rapid_mm_per_s = q16(m.rapid_mm_per_s, "rapid");
  c.control_rate_hz = whole(m.rate_hz, "rate_hz");
  for (std::size_t a = 0; a < axis_count && a < motion_axes; ++a) {
    auto& axis = c.axes[a];
    axis.steps_per_mm = m.axes[a].steps_per_mm;
    axis.min_position_mm = std::numeric_limits<std::int32_t>::min();
    axis.max_position_mm = std::numeric_limits<std::int32_t>::max();
    axis.max_velocity_mm_per_s = m.axes[a].v_max_mm_per_s;
    axis.max_acceleration_mm_per_s2 = m.axes[a].a_max_mm_per_s2;
  }
  return out;
}

protocol::QueueSegment to_wire(const PathSegment& s, const JointStop& entry, std::size_t axis_count, const std::string& where,
                              std::vector<std::string>& notes) {
  protocol::QueueSegment q;
  q.axis_count = static_cast<std::uint8_t>(axis_count);
  q.rapid = s.rapid();
  q.stop_before = entry.stop;
  q.rest_ticks = entry.rest_ticks;
  bool exact = true;
  const auto coordinate = [&](double value) {
    try {
      return to_q16(value, exact);
    } catch (const std::out_of_range& e) {
      throw std::runtime_error(where + e.what());
    }
  };
  const auto put = [&](std::size_t slot, const MachinePoint& p, std::size_t axes) {
    for (std::size_t a = 0; a < axes; ++a) q.points[slot][a] = coordinate(p[a]);
    if (axes < 3 && p[2] != 0) throw std::runtime_error(where + "moves Z, but the controller has 2 axes");
  };
  if (s.feed_mm_per_s() != 0) {
    q.has_feed = true;
    bool feed_exact = true;
    q.feed_mm_per_s = to_q16(s.feed_mm_per_s(), feed_exact);
    if (!feed_exact) notes.push_back(where + "feed " + format_number(s.feed_mm_per_s()) + " rounded to Q16.16");
  }
  switch (s.kind()) {
    case SegmentKind::Line:
    case SegmentKind::Bezier: {
      const auto points = s.polynomial().control_points();
      q.kind = s.kind() == SegmentKind::Line ? protocol::SegmentKind::Line : protocol::SegmentKind::Bezier;
      q.degree = static_cast<std::uint8_t>(points.size() - 1);
      for (std::size_t k = 0; k < points.size(); ++k) put(k, points[k], axis_count);
      break;
    }
    case SegmentKind::RationalBezier: {
      const auto points = s.rational().control_points();
      q.kind = protocol::SegmentKind::RationalBezier;
      q.degree = static_cast<std::uint8_t>(points.size() - 1);
      bool weights_exact = true;
      for (std::size_t k = 0; k < points.size(); ++k) {
        put(k, points[k], axis_count);
        q.weights[k] = to_q16(s.rational().weight(k), weights_exact);
      }
      if (!weights_exact) notes.push_back(where + "weights rounded to Q16.16");
      break;
    }
    case SegmentKind::Arc: {
      q.kind = protocol::SegmentKind::Arc;
      q.degree = 2;
      q.direction = s.arc_sweep_rad() > 0 ? ArcDirection::CounterClockwise : ArcDirection::Clockwise;
      put(0, s.start(), axis_count);
      put(1, s.end(), axis_count);
      q.points[2][0] = coordinate(s.arc_center()[0]);
      q.points[2][1] = coordinate(s.arc_center()[1]);
      q.turns = extra_turns(s, q, where);
      break;
    }
  }
  if (!exact) throw std::runtime_error(where + "a coordinate is not a Q16.16 value (load the job with load_job)");
  return q;
}

std::string wire_segment_where(const std::string& job_name, std::size_t file_index) {
  return job_name + ": segment " + std::to_string(file_index) + ": ";
}

WireJob to_wire(const Job& job, std::size_t axis_count, double rate_hz) {
  WireJob out;
  out.segments.reserve(job.segments.size());
  const JointStops entries = joint_stops(job, rate_hz);
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    out.segments.push_back(to_wire(job.segments[i], entries[i], axis_count, wire_segment_where(job.name, file_segment(job, i)), out.notes));
    if (i + 1 == job.segments.size()) out.segments.back().end_rest_ticks = entries.at_end().rest_ticks;  // dwells after the last move
  }
  return out;
}

protocol::QueuePiece to_wire(const PlannedPiece& piece, std::size_t axis_count) {
  const std::string where = "segment " + std::to_string(piece.segment) + ": a planned piece";
  if (!valid_piece_ticks(piece.ticks, piece.exact_run, piece.rest)) {
    throw std::runtime_error(where + " covers " + std::to_string(piece.ticks) + " ticks, not " +
                             (piece.rest        ? "1 to " + std::to_string(max_rest_ticks) + " (a rest)"
                              : piece.exact_run ? "2 to " + std::to_string(max_exact_run) + " (an exact run)"
                                                : "1 or a power of two up to " + std::to_string(HermiteChunk::max_ticks)));
  }
  const std::size_t sent = piece.exact_run ? piece.ticks - 1 : is_chunk(piece) ? piece.controls.size() : 0;
  protocol::QueuePiece q;
  q.exact_run = piece.exact_run;
  q.rest = piece.rest;
  q.axis_count = static_cast<std::uint8_t>(axis_count);
  q.ticks = static_cast<std::uint16_t>(piece.ticks);
  q.end_of_job = piece.end_of_job;
  q.segment = piece.segment;
  const auto put = [&](const MachinePoint& p, std::array<double, protocol::max_axes>& out, const char* what) {
    for (std::size_t a = 0; a < axis_count && a < motion_axes; ++a) out[a] = p[a];
    if (axis_count < 3 && p[2] != 0) {
      throw std::runtime_error(where + "'s " + what + " has z = " + format_number(p[2]) + ", but the controller has 2 axes");
    }
  };
  put(piece.end, q.end, "end point");
  for (std::size_t k = 0; k < sent; ++k) put(piece.controls[k], q.controls[k], piece.exact_run ? "run point" : "control point");
  return q;
}

namespace {

/// The wire kind of a job event, or none for what the controller does not act on.
std::optional<protocol::MachineEventKind> wire_kind(JobEventKind kind) {
  using protocol::MachineEventKind;
  switch (kind) {
    case JobEventKind::SpindleOn: return MachineEventKind::SpindleOn;
    case JobEventKind::SpindleOff: return MachineEventKind::SpindleOff;
    case JobEventKind::SpindleSpeed: return MachineEventKind::SpindleSpeed;
    case JobEventKind::CoolantMist: return MachineEventKind::CoolantMist;
    case JobEventKind::CoolantFlood: return MachineEventKind::CoolantFlood;
    case JobEventKind::CoolantOff: return MachineEventKind::CoolantOff;
    case JobEventKind::DigitalOutput: return MachineEventKind::DigitalOutput;
    case JobEventKind::PenUp: return MachineEventKind::PenUp;
    case JobEventKind::PenDown: return MachineEventKind::PenDown;
    case JobEventKind::ToolChange: return MachineEventKind::ToolChange;
    case JobEventKind::ProgramPause: return MachineEventKind::ProgramPause;
    case JobEventKind::LayerChange: return MachineEventKind::LayerChange;
    case JobEventKind::ProgramEnd: return MachineEventKind::ProgramEnd;
    case JobEventKind::Dwell:
    case JobEventKind::Message: return std::nullopt;
  }
  return std::nullopt;
}

/// An event's value as a u32: rev/min rounded, an output or tool number whole.
std::uint32_t wire_value(const Job& job, const JobEvent& event) {
  const double value = event.kind == JobEventKind::SpindleOn || event.kind == JobEventKind::SpindleSpeed ? std::nearbyint(event.value)
                                                                                                       : event.value;
  if (!(value >= 0 && value <= 4294967295.0) || value != std::floor(value)) {
    throw std::runtime_error(job.name + (event.line > 0 ? ":" + std::to_string(event.line) : std::string{}) + ": " + event.text +
                             ": value " + format_number(event.value) + " does not travel as a whole number 0 .. 2^32 - 1");
  }
  return static_cast<std::uint32_t>(value);
}

}  // namespace

namespace {

/// The events of `job`; `label_of(k)` labels the joint into segment k (past
/// the last, the job's end).
template <class LabelOf>
std::vector<protocol::QueueEvent> wire_events(const Job& job, double rate_hz, const LabelOf& label_of) {
  std::vector<protocol::QueueEvent> out;
  std::size_t joint = ~std::size_t{0};
  std::uint64_t rested = 0;  // the dwell ticks at this joint so far
  for (const JobEvent& event : job.events) {
    if (event.before_segment != joint) {
      joint = event.before_segment;
      rested = 0;
    }
    if (event.kind == JobEventKind::Dwell) {
      rested += dwell_ticks(event.value, rate_hz);
      continue;
    }
    const auto kind = wire_kind(event.kind);
    if (!kind) continue;
    protocol::QueueEvent e;
    e.kind = *kind;
    e.flag = event.flag;
    e.value = wire_value(job, event);
    e.after_rest_ticks = static_cast<std::uint32_t>(rested);
    e.segment = static_cast<std::uint32_t>(label_of(joint));
    out.push_back(e);
  }
  return out;
}

}  // namespace

std::vector<protocol::QueueEvent> to_wire_events(const Job& job, double rate_hz, const std::map<std::size_t, std::size_t>& labels) {
  return wire_events(job, rate_hz, [&](std::size_t k) {
    const auto found = labels.find(k);
    if (found == labels.end()) throw std::logic_error("to_wire_events: no label for the joint into segment " + std::to_string(k));
    return found->second;
  });
}

std::vector<protocol::QueueEvent> to_wire_events(const Job& job, double rate_hz, const std::function<std::size_t(std::size_t)>& label_of) {
  return wire_events(job, rate_hz, label_of);
}

namespace {

/// `segment` as the device sees it: through the wire (its errors begin with `where`) and the
/// firmware's conversion (its refusal begins with `refused_where`).
PathSegment device_view(const PathSegment& segment, const JointStop& entry, const std::string& where, const std::string& refused_where) {
  std::vector<std::string> notes;  // what the wire rounds is the device's too
  const auto seen = firmware::to_path_segment(to_wire(segment, entry, motion_axes, where, notes));
  if (!seen) throw std::runtime_error(refused_where + std::string(describe(seen.error())));
  return seen.value();
}

/// The segments of `inner` as the device sees them (device_view, errors naming the file segment).
class DeviceViewSegments final : public SegmentSource {
 public:
  DeviceViewSegments(std::unique_ptr<SegmentSource> inner, std::string name) : inner_(std::move(inner)), name_(std::move(name)) {}

  const PathSegment* next(std::size_t& source) override {
    const PathSegment* segment = inner_->next(source);
    if (segment == nullptr) return nullptr;
    const std::string where = wire_segment_where(name_, source);
    current_ = device_view(*segment, JointStop{}, where, where);
    return &*current_;
  }

 private:
  std::unique_ptr<SegmentSource> inner_;
  std::string name_;
  std::optional<PathSegment> current_;
};

}  // namespace

MachineLimits as_device_sees(const MachineLimits& machine) {
  const auto limits = firmware::to_machine_limits(to_wire(machine, motion_axes).configuration);
  if (!limits) throw std::runtime_error("machine: " + std::string(describe(limits.error())));
  return limits.value();
}

ReadableJob as_device_sees(const ReadableJob& job) {
  ReadableJob seen = job;
  seen.read = [read = job.read, name = job.outline->name] { return std::make_unique<DeviceViewSegments>(read(), name); };
  return seen;
}

std::pair<Job, MachineLimits> as_device_sees(const Job& job, const MachineLimits& machine) {
  const MachineLimits limits = as_device_sees(machine);
  const JointStops entries = joint_stops(job, machine.rate_hz);
  Job seen = job;
  seen.segments.clear();
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    // The wire's errors name the file segment (as to_wire(Job) does), the firmware's refusal the job's.
    seen.segments.push_back(
        device_view(job.segments[i], entries[i], wire_segment_where(job.name, file_segment(job, i)), wire_segment_where(job.name, i)));
  }
  return {seen, limits};
}

}  // namespace curvestep::host::link
