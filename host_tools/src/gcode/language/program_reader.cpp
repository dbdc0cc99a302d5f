// SPDX-License-Identifier: MIT
// The language layer's executor: a program counter over the program's lines, a stack of call frames
// (each with its saved #1-#30, its local named parameters and its repeat counters) and the links
// found by the StructureScan. Lines run lazily, one next() at a time, so every expression reads the
// parameters as the machine layer left them after the previous block. The lines are read from a
// LineSource as they run: forward, and by a seek for a jump (always to an O-word line or the line
// after one, whose places the structure pre-scan keeps).
#include <curvestep/host/gcode/program_reader.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include <curvestep/host/load_error.hpp>

#include "line_parser.hpp"
#include "line_source.hpp"
#include "message_text.hpp"
#include "program_structure.hpp"

namespace curvestep::host::gcode {

using detail::ControlLink;
using detail::Keyword;
using detail::LineError;
using detail::no_line;
using detail::OWord;
using detail::ParsedLine;

namespace {

/// #1-#30: a call's arguments, saved and restored around each call.
constexpr int argument_parameters = 30;
/// A repeat count beyond this is cut to it (the line budget stops such a loop anyway).
constexpr double max_repeat_count = 1e15;

struct Frame {
  std::size_t return_line = no_line;
  std::array<double, argument_parameters> saved{};
  std::map<std::string, double> locals;
  std::map<std::size_t, long long> repeats;  ///< repeat line -> passes still to run
};

bool is_global(const std::string& name) { return !name.empty() && name.front() == '_'; }

/// Where an O-word line and the line after it start in the file: control flow jumps to these
/// lines only, so no other line's place is kept.
struct JumpTarget {
  std::size_t line = no_line;     ///< the O-word line, 0-based
  std::uint64_t offset = 0;       ///< where it starts
  std::uint64_t next_offset = 0;  ///< where the line after it starts
};

/// A line read from the file, parsed.
struct ReadLine {
  std::string source;  ///< as written, without '\r'
  ParsedLine parsed;
};

/// Lines read lately that the reader keeps parsed (about 0.7 KB each): the lines of a loop with
/// fewer run again without being read and parsed again. A program without O-words runs each line
/// once and keeps only the last.
constexpr std::size_t recent_lines_kept = 256;

/// A line as the parser reads it: without the '\r' of a CRLF line end.
std::string_view without_carriage_return(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

}  // namespace

class ProgramReader::Impl final : public detail::ParameterSource {
 public:
  Impl(std::unique_ptr<detail::LineSource> source, std::string file_name, ProgramOptions options)
      : source_(std::move(source)), file_(std::move(file_name)), options_(options) {
    prescan();
    source_->seek(0);
    frames_.emplace_back();
    store_.set_named("_value", 0.0);
    store_.set_named("_value_returned", 0.0);
  }

  std::optional<ProgramBlock> next() {
    try {
      while (!ended_) {
        if (pc_ >= end_) {
          ended_ = true;
          break;
        }
        forget_lines();  // no line of an earlier step is looked at again
        count_line();
        const ParsedLine& line = parsed(pc_);
        if (skipped(line)) {
          ++pc_;
          continue;
        }
        if (line.error) throw *line.error;
        if (line.oword) {
          run_control();
          continue;
        }
        if (auto block = run_line()) return block;
      }
    } catch (const LineError& error) {
      ended_ = true;
      throw_at(pc_, error);
    } catch (...) {
      ended_ = true;
      throw;
    }
    return std::nullopt;
  }

  ParameterStore& parameters() noexcept { return store_; }
  [[nodiscard]] bool ended() const noexcept { return ended_; }
  [[nodiscard]] std::size_t call_depth() const noexcept { return frames_.size() - 1; }
  [[nodiscard]] std::size_t line_count() const noexcept { return line_count_; }

  [[nodiscard]] double numbered(int number) const override { return store_.get(number); }
  [[nodiscard]] std::optional<double> named(const std::string& name) const override {
    if (is_global(name)) return store_.named(name);
    const auto& locals = frames_.back().locals;
    const auto found = locals.find(name);
    if (found == locals.end()) return std::nullopt;
    return found->second;
  }

 private:
  /// The structure pre-scan, one read of the whole file: counts its lines (refusing more than
  /// max_lines before anything else), parses each line up to the closing '%' and hands the O-word
  /// lines that can run to the structure scan. The first error is thrown after the count: an
  /// O-word line's syntax error, else the first structure error in line order.
  void prescan() {
    detail::StructureScan scan(file_);
    bool opened = false;   // the first non-blank line was '%'
    bool content = false;  // a non-blank line was seen
    bool parsing = true;   // false after the closing '%' or a syntax error
    std::optional<std::pair<std::size_t, LineError>> syntax_error;
    std::optional<LoadError> structure_error;
    std::size_t index = 0;
    for (std::uint64_t offset = source_->offset();; offset = source_->offset(), ++index) {
      const auto read = source_->next();
      if (!read) break;
      const bool written = !(read->empty() && source_->at_end());  // a last '\n' ends a line, it does not start one
      if (written && index >= options_.max_lines) {
        throw LoadError(SourceLocation{file_, options_.max_lines + 1, 1, std::nullopt, {}, {}},
                        "the program has more than " + std::to_string(options_.max_lines) +
                            " lines, the most a G-code file may have (docs/robustness.md): split it into several files",
                        Error::CapacityExceeded);
      }
      if (written) line_count_ = index + 1;
      if (!parsing) continue;
      ParsedLine parsed;
      try {
        parsed = detail::parse_program_line(without_carriage_return(*read));
      } catch (const LineError& failure) {
        syntax_error.emplace(index, failure);
        parsing = false;
        continue;
      }
      if (parsed.percent && opened) {  // LinuxCNC reads nothing after the closing '%'
        end_ = index;
        parsing = false;
      }
      if (parsed.percent && !content) opened = true;
      if (!detail::is_blank(parsed)) content = true;
      if (parsed.oword && !(parsed.block_delete && options_.block_delete)) {
        jump_targets_.push_back(JumpTarget{index, offset, source_->offset()});
        if (!structure_error) {
          try {
            scan.add(index, *parsed.oword);
          } catch (const LoadError& failure) {
            structure_error = failure;
          }
        }
      }
    }
    if (parsing) end_ = index;
    if (syntax_error) throw_at(syntax_error->first, syntax_error->second);
    if (structure_error) throw *structure_error;
    structure_ = scan.finish();
  }

  [[noreturn]] void throw_at(std::size_t line, const LineError& error) const {
    throw LoadError(SourceLocation{file_, line + 1, error.column(), std::nullopt, {}, error.field()}, error.message(), error.code());
  }

  [[noreturn]] void fail_oword(const OWord& oword, const std::string& message, Error code) const {
    throw LineError(oword.column, detail::oword_text(oword), message, code);
  }

  /// The budget that turns an endless loop into an error naming the loop.
  void count_line() {
    if (++executed_ <= options_.max_executed_lines) return;
    const std::size_t loop = skipped(parsed(pc_)) ? no_line : structure_.loop_containing(pc_);
    const std::string message = "more than " + std::to_string(options_.max_executed_lines) +
                                " lines executed: an endless loop? (the limit keeps a program from running forever)";
    if (loop != no_line) {
      pc_ = loop;
      fail_oword(oword_at(loop), message, Error::IterationLimit);
    }
    throw LineError(0, {}, message, Error::IterationLimit);
  }

  /// A '%' line, or one starting with '/' while the block delete switch is on.
  bool skipped(const ParsedLine& line) const noexcept { return line.percent || (line.block_delete && options_.block_delete); }

  /// A value of the line at the program counter (parsed last).
  double value(detail::NodeIndex root) const {
    const ReadLine& line = recent_.at(pc_);
    return detail::evaluate(line.parsed.nodes, root, line.source, *this);
  }

  /// The O-word of line `index`, an O-word line.
  const OWord& oword_at(std::size_t index) { return *parsed(index).oword; }

  /// Line `index` parsed: one of the lines read lately, or read from the file and parsed (into
  /// the room of a line forgotten, if any: its text keeps its capacity).
  const ReadLine& line(std::size_t index) {
    const auto found = recent_.find(index);
    if (found != recent_.end()) return found->second;
    if (spare_.empty()) return read_into(recent_[index], index);
    spare_.key() = index;
    read_into(spare_.mapped(), index);
    return recent_.insert(std::move(spare_)).position->second;  // leaves spare_ empty
  }

  const ReadLine& read_into(ReadLine& line, std::size_t index) {
    line.source.assign(without_carriage_return(read_line(index)));
    line.parsed = detail::parse_program_line(line.source);  // cannot throw: the pre-scan parsed every O-word line
    return line;
  }

  /// Forgets the lines read lately once there are as many as the reader keeps, and keeps the room
  /// of one for the next line read.
  void forget_lines() {
    const std::size_t kept = structure_.links.empty() ? 1 : recent_lines_kept;
    if (recent_.size() < kept) return;
    if (spare_.empty()) spare_ = recent_.extract(recent_.begin());
    recent_.clear();
  }

  const ParsedLine& parsed(std::size_t index) { return line(index).parsed; }

  /// Line `index` as written: the next line of the file, or after a seek to where the line starts
  /// (control flow reaches a line out of order only at an O-word line or the line after one).
  std::string_view read_line(std::size_t index) {
    if (index != source_line_) source_->seek(offset_of(index));
    const auto line = source_->next();
    if (!line) {
      throw std::runtime_error(file_ + ": line " + std::to_string(index + 1) +
                               " is past the end of the file: did the file change while it was read?");
    }
    source_line_ = index + 1;
    return *line;
  }

  /// Where line `index` starts: the first line, an O-word line or the line after one.
  std::uint64_t offset_of(std::size_t index) const {
    if (index == 0) return 0;
    const auto after = std::upper_bound(jump_targets_.begin(), jump_targets_.end(), index,
                                        [](std::size_t i, const JumpTarget& target) { return i < target.line; });
    if (after != jump_targets_.begin()) {
      const JumpTarget& target = *std::prev(after);
      if (target.line == index) return target.offset;
      if (target.line + 1 == index) return target.next_offset;
    }
    throw std::logic_error("line " + std::to_string(index + 1) + " reached by a jump");
  }

  /// A line of words, assignments and comments.
  std::optional<ProgramBlock> run_line() {
    const ReadLine& current = line(pc_);
    const ParsedLine& line = current.parsed;
    ProgramBlock block;
    block.line = pc_ + 1;
    block.source = current.source;
    block.block_delete = line.block_delete;
    for (const auto& word : line.words) block.words.push_back(ProgramWord{word.letter, value(word.value), word.column});
    // LinuxCNC: every value on the line is read first; the assignments take effect at its end.
    struct Pending {
      const detail::Assignment* assignment;
      int number;
      double value;
    };
    std::vector<Pending> pending;
    for (const auto& assignment : line.assignments) {
      int number = 0;
      if (assignment.name.empty()) {
        const auto& at = line.nodes[assignment.number];
        number = detail::parameter_number(value(assignment.number), at, current.source);
        if (number > max_program_parameter) {
          throw LineError(assignment.column, detail::node_text(at, current.source),
                          "parameters #" + std::to_string(max_program_parameter + 1) + "-#" + std::to_string(ParameterStore::max_numbered) +
                              " are read-only (the machine state: tool, position)",
                          Error::GcodeBadNumber);
        }
      }
      pending.push_back(Pending{&assignment, number, value(assignment.value)});
    }
    for (const auto& p : pending) {
      if (p.number != 0) {
        store_.set(p.number, p.value);
      } else if (is_global(p.assignment->name)) {
        store_.set_named(p.assignment->name, p.value);
      } else {
        frames_.back().locals[p.assignment->name] = p.value;
      }
    }
    // The comments act when the line executes, after its assignments.
    for (const auto& message : line.messages) {
      block.messages.push_back(ProgramMessage{
          message.kind, message.kind == ProgramMessage::Kind::Message ? message.text : detail::substitute_parameters(message.text, *this)});
    }
    ++pc_;
    if (block.words.empty() && block.messages.empty()) return std::nullopt;
    for (const auto& word : block.words) {
      if (word.letter == 'M' && (word.value == 2.0 || word.value == 30.0)) ended_ = true;
    }
    return block;
  }

  bool test(const OWord& oword) const { return value(oword.arguments.front()) != 0.0; }

  void run_control() {
    const std::size_t here = pc_;
    const OWord& oword = oword_at(here);
    const ControlLink& link = structure_.link(here);
    switch (oword.keyword) {
      case Keyword::Sub: pc_ = link.closing + 1; break;
      case Keyword::Endsub:
      case Keyword::Return: return_from(oword); break;
      case Keyword::Call: call(oword); break;
      case Keyword::If:
        if (test(oword)) {
          pc_ = here + 1;
        } else {
          enter_branch(link.next_branch);
        }
        break;
      case Keyword::Elseif:
      case Keyword::Else: pc_ = structure_.link(link.opening).closing + 1; break;  // the taken branch ends here
      case Keyword::Endif:
      case Keyword::Do: pc_ = here + 1; break;
      case Keyword::While:
        if (link.closes_do) {
          pc_ = test(oword) ? link.opening + 1 : here + 1;
        } else {
          pc_ = test(oword) ? here + 1 : link.closing + 1;
        }
        break;
      case Keyword::Endwhile: pc_ = link.opening; break;
      case Keyword::Repeat: {
        const double count = value(oword.arguments.front());
        const long long passes = count >= 1.0 ? static_cast<long long>(std::min(std::trunc(count), max_repeat_count)) : 0;
        if (passes <= 0) {
          pc_ = link.closing + 1;
        } else {
          frames_.back().repeats[here] = passes - 1;
          pc_ = here + 1;
        }
        break;
      }
      case Keyword::Endrepeat: {
        long long& remaining = frames_.back().repeats[link.opening];
        if (remaining > 0) {
          --remaining;
          pc_ = link.opening + 1;
        } else {
          pc_ = here + 1;
        }
        break;
      }
      case Keyword::Break: pc_ = structure_.link(link.opening).closing + 1; break;
      case Keyword::Continue: {
        const std::size_t loop = link.opening;
        // while: test again; do: its closing while tests; repeat: endrepeat counts the pass.
        pc_ = structure_.link(loop).keyword == Keyword::While ? loop : structure_.link(loop).closing;
        break;
      }
    }
  }

  /// After a false if or elseif: test the following elseifs, else enter the else or leave at endif.
  /// The caller looks at nothing of its line afterwards: a long elseif chain may forget the lines read.
  void enter_branch(std::size_t branch) {
    for (;;) {
      pc_ = branch;
      forget_lines();
      const OWord& oword = oword_at(branch);
      if (oword.keyword != Keyword::Elseif) {
        pc_ = branch + 1;
        return;
      }
      count_line();
      if (test(oword)) {
        pc_ = branch + 1;
        return;
      }
      branch = structure_.link(branch).next_branch;
    }
  }

  void call(const OWord& oword) {
    std::string label = oword.label;
    if (oword.label_value != detail::no_node) {
      const double computed = value(oword.label_value);
      if (!(computed >= 0.0 && computed < 1e9 && computed == std::floor(computed))) {
        fail_oword(oword, "a computed subroutine label must be a whole number 0..999999999", Error::GcodeBadNumber);
      }
      label = std::to_string(static_cast<long>(computed));
    }
    const auto sub = structure_.subs.find(label);
    if (sub == structure_.subs.end()) fail_oword(oword, "no subroutine o" + label + " sub in the file", Error::GcodeSyntax);
    if (call_depth() >= options_.max_call_depth) {
      fail_oword(oword, "subroutine calls nested deeper than " + std::to_string(options_.max_call_depth) + " (endless recursion?)",
                 Error::CapacityExceeded);
    }
    std::vector<double> arguments;
    for (const auto argument : oword.arguments) arguments.push_back(value(argument));
    Frame frame;
    frame.return_line = pc_ + 1;
    for (int n = 1; n <= argument_parameters; ++n) frame.saved[static_cast<std::size_t>(n - 1)] = store_.get(n);
    frames_.push_back(std::move(frame));
    // #N+1..#30 keep the caller's values (LinuxCNC).
    for (std::size_t k = 0; k < arguments.size(); ++k) store_.set(static_cast<int>(k + 1), arguments[k]);
    store_.set_named("_value_returned", 0.0);
    pc_ = sub->second + 1;
  }

  void return_from(const OWord& oword) {
    if (frames_.size() == 1) fail_oword(oword, "reached without a call", Error::GcodeSyntax);
    const bool has_value = !oword.arguments.empty();
    const double result = has_value ? value(oword.arguments.front()) : 0.0;
    store_.set_named("_value", result);
    store_.set_named("_value_returned", has_value ? 1.0 : 0.0);
    const Frame& frame = frames_.back();
    for (int n = 1; n <= argument_parameters; ++n) store_.set(n, frame.saved[static_cast<std::size_t>(n - 1)]);
    pc_ = frame.return_line;
    frames_.pop_back();
  }

  std::unique_ptr<detail::LineSource> source_;
  std::string file_;
  ProgramOptions options_;
  // A program's parse trees would take about 0.7 KB per line, its text about 20 bytes: the reader
  // keeps neither, only where the O-word lines start (jumps go there) and their structure.
  std::vector<JumpTarget> jump_targets_;  ///< one per O-word line, in line order
  detail::ProgramStructure structure_;
  std::size_t end_ = 0;         ///< lines from here on are not part of the program (closing %)
  std::size_t line_count_ = 0;  ///< lines in the file (a last '\n' ends a line, it does not start one)
  std::size_t source_line_ = 0;  ///< the line source_->next() reads
  std::map<std::size_t, ReadLine> recent_;  ///< at most recent_lines_kept lines read lately (and the step's own)
  std::map<std::size_t, ReadLine>::node_type spare_;  ///< a forgotten line's room
  ParameterStore store_;
  std::vector<Frame> frames_;
  std::size_t pc_ = 0;
  std::size_t executed_ = 0;
  bool ended_ = false;
};

ProgramReader::ProgramReader(std::string_view text, std::string file_name, ProgramOptions options)
    : impl_(std::make_unique<Impl>(detail::text_lines(text), std::move(file_name), options)) {}
ProgramReader::ProgramReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ProgramReader ProgramReader::open_file(const std::filesystem::path& path, std::string file_name, ProgramOptions options) {
  return ProgramReader(std::make_unique<Impl>(detail::file_lines(path), std::move(file_name), options));
}
ProgramReader::~ProgramReader() = default;
ProgramReader::ProgramReader(ProgramReader&&) noexcept = default;
ProgramReader& ProgramReader::operator=(ProgramReader&&) noexcept = default;

std::optional<ProgramBlock> ProgramReader::next() { return impl_->next(); }
ParameterStore& ProgramReader::parameters() noexcept { return impl_->parameters(); }
const ParameterStore& ProgramReader::parameters() const noexcept { return impl_->parameters(); }
bool ProgramReader::ended() const noexcept { return impl_->ended(); }
std::size_t ProgramReader::call_depth() const noexcept { return impl_->call_depth(); }
std::size_t ProgramReader::line_count() const noexcept { return impl_->line_count(); }

}  // namespace curvestep::host::gcode
