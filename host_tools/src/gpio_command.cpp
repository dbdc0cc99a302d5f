// SPDX-License-Identifier: MIT
// `curvestep gpio JOB --machine MACHINE.json [--rate HZ] [--chip NAME] [--dry-run]`: runs a job on
// this Linux computer's GPIO lines (step/dir), in real time, through the host board (boards/host).
//
// Nothing here re-implements the controller: the firmware (firmware::App on HostBoard, the loop of
// boards::host::run_device with its clock_nanosleep ticks) runs in a thread on one end of a
// pseudo-terminal, and the job is uploaded to it over the real protocol (link::stream_job), exactly
// as `curvestep device --gpio` + `curvestep stream` would do in two processes. The step/dir edges
// go to GpiodStepOutput (libgpiod), which writes each edge at its step-timer time.
//
// Before anything moves, the job is planned as the device will see it (after the wire's
// conversions) and checked against the machine's max_step_rate and the host board's per-tick step
// capacity (lib/core motion/step_generator.hpp: check_step_rate over peak axis speeds and over the
// setpoints). --dry-run drives no lines: ticks run as fast as the link allows (as `device --fast`)
// and the edges are only counted, so the summary's step counts can be checked without hardware.
// While it runs, the operator's keys and signals (operator_session.hpp: ! hold, ~ resume, Ctrl-X /
// Esc abort, ? status; Ctrl-C holds and asks, SIGTERM aborts) act on the firmware through the
// protocol, as with `curvestep stream`.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <curvestep/boards/host/board.hpp>
#include <curvestep/boards/host/device.hpp>
#include <curvestep/boards/host/gpio_output.hpp>
#include <curvestep/boards/host/gpiod_machine_outputs.hpp>
#include <curvestep/core/error_text.hpp>
#include <curvestep/core/motion/step_generator.hpp>
#include <curvestep/core/motion/step_position.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/job_file.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/link/transport.hpp>
#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/simulator.hpp>
#include <curvestep/host/streamed_job.hpp>

#include "board_thread.hpp"
#include "command_registry.hpp"
#include "gpio_command_output.hpp"
#include "gpio_wiring.hpp"
#include "job_pipeline_options.hpp"
#include "link_options.hpp"
#include "operator_session.hpp"
#include "rate_option.hpp"

namespace curvestep::host {
namespace {

struct GpioCommandOptions {
  std::string job;
  std::string machine;
  double rate_hz = 0;
  std::string chip;
  bool dry_run = false;
  unsigned link_timeout_ms = 3000;
  JobPipelineOptions pipeline;
  bool keys = false;  ///< --keys: operator keys from stdin even if it is no terminal
  StartOverride start_override;  ///< --feed-override, --rapid-override
};

/// Exit status: the job asks an axis for more steps per second than the machine allows.
constexpr int exit_step_rate = 3;
/// Exit status: the controller or the link failed while running.
constexpr int exit_device_error = 4;
/// Exit status: the GPIO chip or a line cannot be opened.
constexpr int exit_gpio_unavailable = 5;

constexpr const char* axis_names[] = {"x", "y", "z"};

/// What the pre-check found.
struct Plan {
  SimulationSummary summary;
  std::array<double, motion_axes> peak_steps_per_s{};  ///< per-tick measure of the setpoints
  std::array<std::int64_t, motion_axes> moved_steps{};  ///< end minus start of the job, in steps
};

/// Plans the job as the device will and refuses it (std::runtime_error, exit_step_rate) if an axis
/// needs more than max_step_rate or a tick more steps than the host board's timing allows.
Plan check_before_moving(const ReadableJob& job, const MachineLimits& machine, int& status) {
  const ReadableJob device_job = link::as_device_sees(job);
  MachineLimits device_machine = link::as_device_sees(machine);
  // The file's own max_step_rate is what the drivers can take (it also travels on the wire as binary64).
  device_machine.max_step_rate_hz = machine.max_step_rate_hz;
  const auto config = StepConfig::create(device_machine, boards::host::HostBoard<boards::host::CountingStepOutput>::step_timing());
  if (!config) {
    if (config.error() == Error::InvalidRate) {
      throw std::runtime_error("rate " + format_number(device_machine.rate_hz) +
                               " Hz: the host board's 1 MHz step timer needs a whole number of microseconds per control tick "
                               "(e.g. 250, 500, 1000, 2000 Hz)");
    }
    throw std::runtime_error("machine: the host board cannot step with it: " + std::string(describe(config.error())));
  }
  // The setpoints are measured as the simulation makes them and kept nowhere. The first is where
  // the machine starts: the firmware's first setpoint declares the position (StepGenerator::reset,
  // no edges); every later one moves the steps from there.
  StepRateMeter<Q16_16> meter(config.value());
  Result<void> measured = ok();
  std::optional<Setpoint<Q16_16>> first;
  Setpoint<Q16_16> last;
  Plan plan;
  plan.summary = simulate_stream(device_job, device_machine, SimulationOptions{}, [&](const SetpointRecord& r) {
    Setpoint<Q16_16> s;
    for (std::size_t a = 0; a < motion_axes; ++a) s.position[a] = Q16_16::from_raw(r.raw_q16[a]);
    if (!first) first = s;
    last = s;
    if (measured) measured = meter.add(s);
  });
  if (!measured) throw std::runtime_error(job.outline->name + ": " + std::string(describe(measured.error())));
  const StepRateReport& report = meter.report();
  plan.peak_steps_per_s = report.peak_steps_per_s;
  for (std::size_t a = 0; a < motion_axes; ++a) {
    const auto steps_at = [&](const Setpoint<Q16_16>& s) {
      const auto fine = fine_step_position(s.position[a], config.value().scale(a));
      return fine ? steps_of_fine_position(fine.value()) : 0;
    };
    plan.moved_steps[a] = first ? steps_at(last) - steps_at(*first) : 0;
  }
  // The driver limit: peak axis speed × steps/mm against max_step_rate (the speed from the
  // simulator's finite differences and from the per-tick step measure, whichever is larger).
  std::array<double, motion_axes> peak_speed{};
  for (std::size_t a = 0; a < motion_axes; ++a) {
    const double steps_per_mm = device_machine.axes[a].steps_per_mm;
    const double needed = std::fmax(plan.summary.peak_step_rate_hz[a], plan.peak_steps_per_s[a]);
    peak_speed[a] = steps_per_mm > 0 ? needed / steps_per_mm : 0.0;
  }
  std::ostringstream refusal;
  if (const auto peak = check_step_rate(peak_speed, device_machine); !peak) {
    const std::size_t a = peak.where() < motion_axes ? peak.where() : 0;
    refusal << "axis " << axis_names[a] << " needs " << peak_speed[a] * device_machine.axes[a].steps_per_mm
            << " steps/s, more than max_step_rate " << device_machine.max_step_rate_hz
            << ": nothing moved (lower v_max, the axis's v_max or rapid)";
  }
  if (refusal.str().empty() && report.violations != 0) {
    refusal << "axis " << axis_names[report.first_violation_axis < motion_axes ? report.first_violation_axis : 0] << ": setpoint "
            << report.first_violation_setpoint << " asks one tick for more steps than the step timing allows ("
            << describe(Error::StepRateTooHigh) << "): nothing moved";
  }
  if (!refusal.str().empty()) {
    std::cerr << "curvestep gpio: " << refusal.str() << "\n";
    status = exit_step_rate;
  }
  return plan;
}

std::string join_steps(const auto& values) {
  std::ostringstream s;
  for (std::size_t a = 0; a < motion_axes; ++a) s << (a == 0 ? "" : "  ") << axis_names[a] << " " << values[a];
  return s.str();
}

template <class Inner>
int run_on_board(const GpioCommandOptions& o, const ReadableJob& job, const MachineLimits& machine, const Plan& plan, Inner* inner,
                 boards::host::MachineOutputHooks* machine_outputs, const std::string& where) {
  CountingOutput<Inner> output(inner);
  link::StreamOptions options;
  options.link.link_timeout_ms = o.link_timeout_ms;
  // What the wire rounds: the first few lines, then a count (an SVG's arcs can give dozens).
  auto warnings = std::make_shared<std::size_t>(0);
  options.warn = [warnings](const std::string& text) {
    constexpr std::size_t shown = 5;
    if (++*warnings <= shown) std::cerr << "curvestep gpio: warning: " << text << "\n";
  };
  // Keys and signals act through the protocol (FeedHold, Resume, Abort), as with `curvestep stream`.
  options.feed_override = o.start_override.value();
  options.setpoint_sink = [](const SetpointRecord&) {};  // counted (setpoints_received), kept nowhere
  OperatorSession session("curvestep gpio", o.keys);
  session.attach(options);
  link::StreamResult result;
  const auto started = std::chrono::steady_clock::now();
  std::string failure;
  {
    BoardThread<CountingOutput<Inner>> board(output, o.dry_run, machine_outputs);
    try {
      auto transport = link::open_port(board.port(), 115200);
      result = link::stream_job(*transport, job, machine, options);
    } catch (const link::StreamError& e) {
      failure = e.what();
    } catch (const link::TransportError& e) {
      failure = e.what();
    }
    session.end_line();
  }  // the board thread stops here; the output's lines go low
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (*warnings > 5) std::cerr << "curvestep gpio: warning: " << *warnings - 5 << " more values rounded for the wire\n";

  std::cout << "curvestep gpio " << o.job << " -> " << where << "\n"
            << "  setpoints:           " << result.setpoints_received << " at " << machine.rate_hz << " Hz (planned "
            << plan.summary.setpoints << ")\n"
            << "  duration:            " << plan.summary.duration_s << " s planned, " << wall_s << " s wall clock\n"
            << "  distance:            " << plan.summary.distance_mm << " mm\n"
            << "  peak step rate:      " << join_steps(plan.peak_steps_per_s) << " steps/s (max_step_rate "
            << machine.max_step_rate_hz << ")\n"
            << "  steps taken:         " << join_steps(output.steps()) << "\n"
            << "  net steps:           " << join_steps(output.net_steps()) << " (planned " << join_steps(plan.moved_steps)
            << ": end minus start position in steps)\n";
  if constexpr (requires(Inner& i) { i.write_errors(); }) {
    if (inner != nullptr) {
      std::cout << "  GPIO write errors:   " << inner->write_errors() << "\n"
                << "  edge clock restarts: " << inner->rebases() << " (1: at the start; more: a pause or the loop fell behind)\n";
    }
  }
  std::cout << format_operator_summary(result, machine.rate_hz);
  session.warn_tick_overruns(result, machine.rate_hz);
  if (!failure.empty()) {
    std::cerr << "curvestep gpio: " << failure << "\n";
    return exit_device_error;
  }
  if (result.aborted) {
    std::cerr << "curvestep gpio: aborted by the operator\n";
    return exit_aborted;
  }
  if (result.standing_ticks != 0) {
    std::cerr << "curvestep gpio: the machine stood still for " << result.standing_ticks << " ticks (feed hold or a starved queue)\n";
  }
  for (std::size_t a = 0; a < motion_axes; ++a) {
    if (output.net_steps()[a] != plan.moved_steps[a]) {
      std::cerr << "curvestep gpio: axis " << axis_names[a] << " moved " << output.net_steps()[a] << " steps, planned "
                << plan.moved_steps[a] << "\n";
      return exit_device_error;
    }
  }
  return 0;
}

int run_gpio(const GpioCommandOptions& o) {
  const MachineFile file = load_machine_file(o.machine);
  MachineLimits machine = file.limits;
  if (o.rate_hz > 0) {
    machine.rate_hz = o.rate_hz;
    if (auto valid = machine.validate(); !valid) throw std::runtime_error("--rate: must be between 100 and 100000 Hz");
  }
  // A streamed job is not held (streamed_job.hpp): the file is read for the plan, for the check
  // below, for the wire's checks and for the upload. A pen drawing is prepared whole.
  const StreamedJobPlan streamed_plan = plan_job(o.job, file, machine, o.pipeline);
  const PreparedJob& prepared = streamed_plan.prepared;
  const Job& job = prepared.job;
  const ReadableJob readable_job = readable(streamed_plan, o.job, file, machine, o.pipeline);
  machine = prepared.machine;
  for (const auto& note : prepared.notes) std::cerr << "curvestep gpio: note: " << note << "\n";
  boards::host::GpioLines lines;
  if (!o.dry_run) {
    if (!file.gpio) {
      throw std::runtime_error(o.machine + ": no \"gpio\" section (chip and step/dir line names; docs/job_format.md)");
    }
    lines = step_lines(*file.gpio, o.chip);
  }
  if (file.gpio) check_digital_outputs(job, *file.gpio);  // an M62-M65 without a line: refused at job load
  // Open the lines first: a missing chip or line is reported before anything else happens.
  std::unique_ptr<boards::host::GpiodStepOutput> gpio;
  std::unique_ptr<boards::host::GpiodMachineOutputs> outputs;  // spindle, coolant, digital outputs, servo pen
  if (!o.dry_run) {
    try {
      // A tick that stood still (a stalled stream) makes the next edges one period late: re-base then.
      const auto half_period_ns = static_cast<std::int64_t>(5e8 / machine.rate_hz);
      gpio = std::make_unique<boards::host::GpiodStepOutput>(
          lines, boards::host::SystemClock::step_timer_hz,
          std::min(boards::host::EdgeClock::default_late_limit_ns, half_period_ns));
      const auto wired = output_lines(*file.gpio, file.pen, o.chip);
      if (wired.any()) outputs = std::make_unique<boards::host::GpiodMachineOutputs>(wired);
    } catch (const boards::host::GpioError& e) {
      std::cerr << "curvestep gpio: " << e.what() << "\n";
      return exit_gpio_unavailable;
    }
  }
  int status = 0;
  const Plan plan = check_before_moving(readable_job, machine, status);
  if (status != 0) return status;
  for (std::size_t a = 0; a < motion_axes; ++a) {
    const bool moves = plan.peak_steps_per_s[a] > 0;
    if (!o.dry_run && moves && !file.gpio->axes[a]) {
      std::cerr << "curvestep gpio: warning: axis " << axis_names[a] << " steps but has no lines in \"gpio\" (its steps go nowhere)\n";
    }
  }
  std::signal(SIGPIPE, SIG_IGN);
  if (o.dry_run) {
    return run_on_board<boards::host::GpiodStepOutput>(o, readable_job, machine, plan, nullptr, nullptr, "dry run (no lines driven)");
  }
  return run_on_board(o, readable_job, machine, plan, gpio.get(), outputs ? &outputs->hooks() : nullptr, "GPIO chip \"" + lines.chip + "\"");
}

void add_gpio_command(CLI::App& app) {
  auto options = std::make_shared<GpioCommandOptions>();
  auto* gpio = app.add_subcommand("gpio", "Run a job in real time on this computer's GPIO step/dir lines (libgpiod)");
  gpio->add_option("job", options->job, job_file_help())->required()->check(CLI::ExistingFile);
  gpio->add_option("--machine,-m", options->machine, "Machine file (.json) with a \"gpio\" section naming the chip and lines")
      ->required()
      ->check(CLI::ExistingFile);
  gpio->add_option("--rate", options->rate_hz, "Control tick rate in Hz (100..100000, dividing 1 MHz), overriding the machine file")
      ->check(rate_hz_check());
  gpio->add_option("--chip", options->chip, "GPIO chip (gpiochip0, /dev/gpiochip0 or 0), overriding the machine file's gpio.chip");
  gpio->add_flag("--dry-run", options->dry_run,
                 "Drive no lines: run the firmware as fast as possible and count the steps it would take");
  add_link_timeout_option(*gpio, options->link_timeout_ms);
  add_keys_option(*gpio, options->keys, "! hold, ~ resume, Ctrl-X or Esc abort, ? status, ] [ } { = ( * ) overrides");
  add_start_override_options(*gpio, options->start_override);
  add_job_pipeline_options(gpio, options->pipeline);
  gpio->footer(
      std::string("While a job runs: ! feed hold, ~ resume, Ctrl-X or Esc abort, ? status line (keys from a terminal on stdin, or --keys);\n") +
      override_keys_footer +
      "Ctrl-C holds and asks (a second Ctrl-C aborts), SIGTERM aborts.\n"
      "Exit status: 0 done; 3 an axis would exceed max_step_rate (nothing moved); 4 the controller or link failed;\n"
      "5 the GPIO chip or a line cannot be opened; 6 aborted by the operator; 1 bad input.");
  gpio->callback([options] {
    const int status = run_gpio(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

const RegisterCommand registered{65, add_gpio_command};

}  // namespace
}  // namespace curvestep::host
