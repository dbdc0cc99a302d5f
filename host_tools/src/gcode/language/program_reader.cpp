// SPDX-License-Identifier: MIT
// The language layer's executor: a program counter over the program's lines, a stack of call frames
// (each with its saved #1-#30, its local named parameters and its repeat counters) and the links
// found by the StructureScan. Lines run lazily, one next() at a time, so every expression reads the
// parameters as the machine layer left them after the previous block. The lines are read from a
// LineSource as they run: forward, and by a seek for a jump (always to an O-word line or the line
// after one, whose places the structure pre-scan keeps). A call to a sub the program does not
// define reads its file (LinuxCNC's SUBROUTINE_PATH): each file is a Unit of its own, with its
// own source, structure and lines read lately, and the program counter names a unit and a line.
// Numbered programs (Fanuc style, LinuxCNC's M98/M99): `M98 P100 L3` runs `O100` ... `M99` of the
// same file three times, with #1-#30 global; the lines after M98 and M99 lines are jump targets too.
#include <curvestep/host/gcode/program_reader.hpp>

#include <algorithm>
#include <array>
#include <cctype>
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
#include "numbered_program.hpp"
#include "program_structure.hpp"

namespace curvestep::host::gcode {

using detail::ControlLink;
using detail::NumberedCall;
using detail::whole_number;
using detail::max_label;
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
  std::size_t return_unit = 0;  ///< the file the call is in (0: the program)
  std::size_t return_line = no_line;
  bool numbered = false;        ///< an M98 call: #1-#30 are global, `saved` is not restored
  std::size_t body = no_line;   ///< M98: the numbered program's O line (each pass starts after it)
  long long passes_left = 0;    ///< M98 L: the passes still to run after this one
  std::array<double, argument_parameters> saved{};
  std::map<std::string, double> locals;
  std::map<std::size_t, long long> repeats;  ///< repeat line -> passes still to run
};

bool is_global(const std::string& name) { return !name.empty() && name.front() == '_'; }

/// Where an O-word, M98 or M99 line and the line after it start in the file: control flow jumps to
/// these lines only, so no other line's place is kept.
struct JumpTarget {
  std::size_t line = no_line;     ///< the O-word, M98 or M99 line, 0-based
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

/// One file of the program: the program itself (unit 0) or a subroutine file, each read as a
/// stream with its own structure, its own jump targets and its own lines read lately.
struct Unit {
  std::unique_ptr<detail::LineSource> source;
  std::string file;  ///< the name messages give
  // A program's parse trees would take about 0.7 KB per line, its text about 20 bytes: the reader
  // keeps neither, only where the O-word lines start (jumps go there) and their structure.
  std::vector<JumpTarget> jump_targets;  ///< one per O-word, M98 and M99 line, in line order
  detail::ProgramStructure structure;
  std::size_t end = 0;          ///< lines from here on are not part of the file (closing %)
  std::size_t line_count = 0;   ///< lines in the file (a last '\n' ends a line, it does not start one)
  std::size_t source_line = 0;  ///< the line source->next() reads
  std::map<std::size_t, ReadLine> recent;  ///< at most recent_lines_kept lines read lately (and the step's own)
  std::map<std::size_t, ReadLine>::node_type spare;  ///< a forgotten line's room
};

/// A subroutine read from its own file.
struct SubFile {
  std::size_t unit = 0;  ///< its Unit
  std::size_t line = 0;  ///< its `sub` line there, 0-based
};

/// The file a call looks for: the label without its brackets, + ".ngc" (LinuxCNC: the name is
/// lower case already, and may hold lower-case letters, digits, '-' and '_'), or an empty string
/// for a name no file may have.
std::string sub_file_name(const std::string& label) {
  const std::string name = label.front() == '<' ? label.substr(1, label.size() - 2) : label;
  for (const char c : name) {
    const auto byte = static_cast<unsigned char>(c);
    if (!(std::islower(byte) || std::isdigit(byte) || c == '-' || c == '_')) return {};
  }
  return name + ".ngc";
}

/// A folder as messages name it.
std::string folder_text(const std::filesystem::path& folder) { return folder.empty() ? std::string(".") : folder.string(); }

}  // namespace

class ProgramReader::Impl final : public detail::ParameterSource {
 public:
  Impl(std::unique_ptr<detail::LineSource> source, std::string file_name, ProgramOptions options) : options_(std::move(options)) {
    auto program = std::make_unique<Unit>();
    program->source = std::move(source);
    program->file = std::move(file_name);
    prescan(*program);
    program->source->seek(0);
    units_.push_back(std::move(program));
    frames_.emplace_back();
    store_.set_named("_value", 0.0);
    store_.set_named("_value_returned", 0.0);
  }

  std::optional<ProgramBlock> next() {
    try {
      while (!ended_) {
        if (pc_ >= unit().end) {
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
  [[nodiscard]] std::size_t line_count() const noexcept { return units_.front()->line_count; }

  [[nodiscard]] double numbered(int number) const override { return store_.get(number); }
  [[nodiscard]] std::optional<double> named(const std::string& name) const override {
    if (is_global(name)) return store_.named(name);
    const auto& locals = frames_.back().locals;
    const auto found = locals.find(name);
    if (found == locals.end()) return std::nullopt;
    return found->second;
  }

 private:
  /// The file the program counter is in.
  Unit& unit() noexcept { return *units_[unit_]; }
  const Unit& unit() const noexcept { return *units_[unit_]; }

  /// The structure pre-scan, one read of the whole file: counts its lines (refusing more than
  /// max_lines before anything else), parses each line up to the closing '%' and hands the O-word
  /// lines that can run to the structure scan. The first error is thrown after the count: an
  /// O-word line's syntax error, else the first structure error in line order. Other lines keep
  /// their syntax errors until they run; the first of those before the O-word line's is named
  /// beside it, so one run shows both (else the user fixes the O-word line to meet the earlier one).
  void prescan(Unit& file) {
    detail::StructureScan scan(file.file);
    bool opened = false;   // the first non-blank line was '%'
    bool content = false;  // a non-blank line was seen
    bool started = false;  // a line other than blanks, comments and '%' was seen (an O100 after it is no program number)
    bool parsing = true;   // false after the closing '%' or a syntax error
    std::optional<std::pair<std::size_t, LineError>> syntax_error;
    std::optional<std::pair<std::size_t, LineError>> kept_error;  // the first other line's, raised if it runs
    std::optional<LoadError> structure_error;
    std::size_t index = 0;
    for (std::uint64_t offset = file.source->offset();; offset = file.source->offset(), ++index) {
      const auto read = file.source->next();
      if (!read) break;
      const bool written = !(read->empty() && file.source->at_end());  // a last '\n' ends a line, it does not start one
      if (written && index >= options_.max_lines) {
        throw LoadError(SourceLocation{file.file, options_.max_lines + 1, 1, std::nullopt, {}, {}},
                        "the program has more than " + std::to_string(options_.max_lines) +
                            " lines, the most a G-code file may have (docs/robustness.md): split it into several files",
                        Error::CapacityExceeded);
      }
      if (written) file.line_count = index + 1;
      if (!parsing) continue;
      ParsedLine parsed;
      try {
        parsed = detail::parse_program_line(without_carriage_return(*read));
      } catch (const LineError& failure) {
        syntax_error.emplace(index, failure);
        parsing = false;
        continue;
      }
      if (parsed.error && !kept_error && !(parsed.block_delete && options_.block_delete)) kept_error.emplace(index, *parsed.error);
      if (parsed.percent && opened) {  // LinuxCNC reads nothing after the closing '%'
        file.end = index;
        parsing = false;
      }
      if (parsed.percent && !content) opened = true;
      if (!detail::is_blank(parsed)) content = true;
      const bool first_line = !started;
      if (!detail::is_blank(parsed) && !parsed.percent) started = true;
      if (parsed.block_delete && options_.block_delete) continue;  // never runs
      const detail::WordValue* m99 = detail::literal_m_word(parsed, 99);
      if (parsed.oword || m99 || detail::literal_m_word(parsed, 98)) file.jump_targets.push_back(JumpTarget{index, offset, file.source->offset()});
      if ((parsed.oword || m99) && !structure_error) {
        try {
          if (parsed.oword) {
            scan.add(index, *parsed.oword, first_line);
          } else {
            scan.add_m99(index, m99->column);
          }
        } catch (const LoadError& failure) {
          structure_error = failure;
        }
      }
    }
    if (parsing) file.end = index;
    if (syntax_error) {
      const auto& [line, failure] = *syntax_error;
      if (!kept_error) throw_at(file, line, failure);
      const auto& [earlier_line, earlier] = *kept_error;
      const std::string also = format_load_error(location_at(file, earlier_line, earlier), earlier.message());
      throw LoadError(location_at(file, line, failure), failure.message() + " (before it, " + also + ")", failure.code());
    }
    if (structure_error) throw *structure_error;
    file.structure = scan.finish();
  }

  /// Where `error` of 0-based `line` of `file` is.
  [[nodiscard]] static SourceLocation location_at(const Unit& file, std::size_t line, const LineError& error) {
    return SourceLocation{file.file, line + 1, error.column(), std::nullopt, {}, error.field()};
  }
  [[noreturn]] void throw_at(const Unit& file, std::size_t line, const LineError& error) const {
    throw LoadError(location_at(file, line, error), error.message(), error.code());
  }
  [[noreturn]] void throw_at(std::size_t line, const LineError& error) const { throw_at(unit(), line, error); }

  [[noreturn]] void fail_oword(const OWord& oword, const std::string& message, Error code) const {
    throw LineError(oword.column, detail::oword_text(oword), message, code);
  }

  /// The budget that turns an endless loop into an error naming the loop.
  void count_line() {
    if (++executed_ <= options_.max_executed_lines) return;
    const std::size_t loop = skipped(parsed(pc_)) ? no_line : unit().structure.loop_containing(pc_);
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
    const ReadLine& line = unit().recent.at(pc_);
    return detail::evaluate(line.parsed.nodes, root, line.source, *this);
  }

  /// The O-word of line `index`, an O-word line.
  const OWord& oword_at(std::size_t index) { return *parsed(index).oword; }

  /// Line `index` of the current file parsed: one of the lines read lately, or read from the file
  /// and parsed (into the room of a line forgotten, if any: its text keeps its capacity).
  const ReadLine& line(std::size_t index) {
    Unit& file = unit();
    const auto found = file.recent.find(index);
    if (found != file.recent.end()) return found->second;
    if (file.spare.empty()) return read_into(file.recent[index], index);
    file.spare.key() = index;
    read_into(file.spare.mapped(), index);
    return file.recent.insert(std::move(file.spare)).position->second;  // leaves the spare empty
  }

  const ReadLine& read_into(ReadLine& line, std::size_t index) {
    line.source.assign(without_carriage_return(read_line(index)));
    line.parsed = detail::parse_program_line(line.source);  // cannot throw: the pre-scan parsed every O-word line
    return line;
  }

  /// Forgets the lines of the current file read lately once there are as many as the reader keeps,
  /// and keeps the room of one for the next line read.
  void forget_lines() {
    Unit& file = unit();
    const std::size_t kept = file.structure.links.empty() ? 1 : recent_lines_kept;
    if (file.recent.size() < kept) return;
    if (file.spare.empty()) file.spare = file.recent.extract(file.recent.begin());
    file.recent.clear();
  }

  const ParsedLine& parsed(std::size_t index) { return line(index).parsed; }

  /// Line `index` as written: the next line of the file, or after a seek to where the line starts
  /// (control flow reaches a line out of order only at an O-word line or the line after one).
  std::string_view read_line(std::size_t index) {
    Unit& file = unit();
    if (index != file.source_line) file.source->seek(offset_of(file, index));
    const auto line = file.source->next();
    if (!line) {
      throw std::runtime_error(file.file + ": line " + std::to_string(index + 1) +
                               " is past the end of the file: did the file change while it was read?");
    }
    file.source_line = index + 1;
    return *line;
  }

  /// Where line `index` of `file` starts: the first line, an O-word line or the line after one.
  static std::uint64_t offset_of(const Unit& file, std::size_t index) {
    if (index == 0) return 0;
    const auto after = std::upper_bound(file.jump_targets.begin(), file.jump_targets.end(), index,
                                        [](std::size_t i, const JumpTarget& target) { return i < target.line; });
    if (after != file.jump_targets.begin()) {
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
    block.program_line = block.line;
    if (unit_ != 0) {
      block.file = unit().file;
      // The line of the program that called into the files: the latest call made from it.
      for (auto frame = frames_.rbegin(); frame != frames_.rend(); ++frame) {
        if (frame->return_unit == 0) {
          block.program_line = frame->return_line;  // the line after the call, 0-based: the call's own, 1-based
          break;
        }
      }
    }
    block.source = current.source;
    block.block_delete = line.block_delete;
    const detail::WordValue* m98 = detail::literal_m_word(line, 98);
    const detail::WordValue* m99 = detail::literal_m_word(line, 99);
    if (m98 && m99) throw LineError(m99->column, "M99", "M98 and M99 cannot share a line", Error::GcodeConflictingWords);
    if (const auto* p = detail::word_of(line, 'P'); m99 && p) {
      throw LineError(p->column, "P", "M99 P (a return to a line number) is not supported: M99 returns to the line after the M98",
                      Error::GcodeSyntax);
    }
    const std::optional<NumberedCall> numbered = m98 ? std::optional(numbered_call(line, *m98)) : std::nullopt;
    if (m99) check_numbered_return(*m99);
    for (const auto& word : line.words) {
      if (&word == m98 || &word == m99 || (m98 && (word.letter == 'P' || word.letter == 'L'))) continue;  // control flow, not the machine's
      const double number = value(word.value);
      if (word.letter == 'M' && (number == 98.0 || number == 99.0)) {
        throw LineError(word.column, "M", "M98 and M99 are control flow, found before the program runs: write them as numbers (M98, M99), "
                        "not computed", Error::GcodeSyntax);
      }
      block.words.push_back(ProgramWord{word.letter, number, word.column});
    }
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
    if (numbered) enter_numbered(*numbered);
    if (m99) return_numbered();
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
    const detail::ProgramStructure& structure = unit().structure;
    const ControlLink& link = structure.link(here);
    switch (oword.keyword) {
      case Keyword::Sub: pc_ = link.closing + 1; break;
      case Keyword::Program: pc_ = link.closing == no_line ? here + 1 : link.closing + 1; break;  // the main program's number, or a definition
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
      case Keyword::Else: pc_ = structure.link(link.opening).closing + 1; break;  // the taken branch ends here
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
      case Keyword::Break: pc_ = structure.link(link.opening).closing + 1; break;
      case Keyword::Continue: {
        const std::size_t loop = link.opening;
        // while: test again; do: its closing while tests; repeat: endrepeat counts the pass.
        pc_ = structure.link(loop).keyword == Keyword::While ? loop : structure.link(loop).closing;
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
      branch = unit().structure.link(branch).next_branch;
    }
  }

  void call(const OWord& oword) {
    std::string label = oword.label;
    if (oword.label_value != detail::no_node) {
      const auto computed = whole_number(value(oword.label_value), max_label, 0.0);
      if (!computed) fail_oword(oword, "a computed subroutine label must be a whole number 0..999999999", Error::GcodeBadNumber);
      label = std::to_string(*computed);
    }
    const SubFile sub = find_sub(oword, label);
    if (call_depth() >= options_.max_call_depth) fail_oword(oword, depth_message(), Error::CapacityExceeded);
    std::vector<double> arguments;
    for (const auto argument : oword.arguments) arguments.push_back(value(argument));
    Frame& frame = push_frame(pc_ + 1);
    for (int n = 1; n <= argument_parameters; ++n) frame.saved[static_cast<std::size_t>(n - 1)] = store_.get(n);
    // #N+1..#30 keep the caller's values (LinuxCNC).
    for (std::size_t k = 0; k < arguments.size(); ++k) store_.set(static_cast<int>(k + 1), arguments[k]);
    store_.set_named("_value_returned", 0.0);
    unit_ = sub.unit;
    pc_ = sub.line + 1;
  }

  /// A new call frame returning to `return_line` of the current file.
  Frame& push_frame(std::size_t return_line) {
    Frame& frame = frames_.emplace_back();
    frame.return_unit = unit_;
    frame.return_line = return_line;
    return frame;
  }

  /// Back to where the innermost call frame returns, and the frame gone.
  void pop_frame() {
    unit_ = frames_.back().return_unit;
    pc_ = frames_.back().return_line;
    frames_.pop_back();
  }

  [[nodiscard]] std::string depth_message() const {
    return "subroutine calls nested deeper than " + std::to_string(options_.max_call_depth) + " (endless recursion?)";
  }

  /// `M98 P- [L-]` of the line at the program counter (numbered_program.hpp), within the call depth.
  NumberedCall numbered_call(const ParsedLine& line, const detail::WordValue& m98) const {
    const NumberedCall call =
        detail::numbered_call(line, m98, [this](detail::NodeIndex root) { return value(root); }, unit().structure, unit().file, max_repeat_count);
    if (call.passes > 0 && call_depth() >= options_.max_call_depth) throw LineError(m98.column, "M98", depth_message(), Error::CapacityExceeded);
    return call;
  }

  /// Runs the numbered program of an M98 (the program counter is on the line after the M98).
  void enter_numbered(const NumberedCall& call) {
    if (call.passes <= 0) return;  // M98 L0 runs nothing
    Frame& frame = push_frame(pc_);
    frame.numbered = true;
    frame.body = call.body;
    frame.passes_left = call.passes - 1;
    pc_ = call.body + 1;
  }

  /// An M99 at the program counter must end a numbered program, not the main program.
  void check_numbered_return(const detail::WordValue& m99) const {
    const ControlLink& link = unit().structure.link(pc_);
    if (link.opening == no_line) detail::fail_main_program_m99(unit().structure, m99);
    if (!frames_.back().numbered || frames_.back().body != link.opening) {
      throw std::logic_error("M99 of a numbered program reached without its M98");
    }
  }

  /// After an M99 (checked): the next pass of the numbered program, or the line after its M98.
  void return_numbered() {
    Frame& frame = frames_.back();
    if (frame.passes_left > 0) {
      --frame.passes_left;
      pc_ = frame.body + 1;
      return;
    }
    pop_frame();
  }

  /// Where sub `label` is: in the program (LinuxCNC's subs are global, so a subroutine file may call
  /// them too), in a subroutine file read before, or in its own file, read now.
  SubFile find_sub(const OWord& oword, const std::string& label) {
    if (unit().structure.numbered.count(label) != 0) {
      fail_oword(oword,
                 "o" + label + " is a numbered program (O" + label + " ... M99): call it with M98 P" + label + "; o" + label +
                     " call calls a sub (o" + label + " sub ... endsub)",
                 Error::GcodeSyntax);
    }
    const auto& program_subs = units_.front()->structure.subs;
    const auto in_program = program_subs.find(label);
    if (in_program != program_subs.end()) return SubFile{0, in_program->second};
    const auto read_before = sub_files_.find(label);
    if (read_before != sub_files_.end()) return read_before->second;
    const SubFile sub = read_sub_file(oword, label);
    sub_files_.emplace(label, sub);
    return sub;
  }

  /// The file of sub `label`: the first `name.ngc` in the subroutine path, read and checked whole
  /// (its structure, as the program's) before its sub runs. It must define that sub and no other
  /// (LinuxCNC: "a named subroutine file can contain only a single subroutine definition"); the
  /// lines outside the sub (comments, a closing M2) never run.
  SubFile read_sub_file(const OWord& oword, const std::string& label) {
    const std::string name = sub_file_name(label);
    if (name.empty()) {
      fail_oword(oword,
                 "no subroutine o" + label + " sub in the program, and no file can hold it: a subroutine file's name has lower-case "
                 "letters, digits, '-' and '_' only (LinuxCNC)",
                 Error::GcodeSyntax);
    }
    std::string searched;
    for (const auto& folder : options_.subroutine_path) {
      const std::filesystem::path path = folder.empty() ? std::filesystem::path(name) : folder / name;
      std::error_code ignored;
      const auto status = std::filesystem::status(path, ignored);
      if (std::filesystem::exists(status)) return read_sub_file(oword, label, path, status);
      searched += (searched.empty() ? "" : ", ") + folder_text(folder);
    }
    fail_oword(oword,
               "no subroutine o" + label + " sub in the program, and no file " + name +
                   (searched.empty() ? " looked for: no subroutine folder given (the program's folder, the subroutine path)"
                                     : " in " + searched + " (the folders searched, in this order)"),
               Error::GcodeSyntax);
  }

  SubFile read_sub_file(const OWord& oword, const std::string& label, const std::filesystem::path& path,
                        const std::filesystem::file_status& status) {
    const std::string cannot_read = "the subroutine file " + path.string() + " of o" + label + " cannot be read: ";
    if (!std::filesystem::is_regular_file(status)) fail_oword(oword, cannot_read + "it is not a regular file", Error::GcodeSyntax);
    auto file = std::make_unique<Unit>();
    file->file = path.string();
    try {
      file->source = detail::file_lines(path);
      prescan(*file);
      file->source->seek(0);
    } catch (const LoadError&) {
      throw;  // an error in the file names its own file:line
    } catch (const std::runtime_error& failure) {
      fail_oword(oword, cannot_read + failure.what(), Error::GcodeSyntax);
    }
    const auto& subs = file->structure.subs;
    if (subs.empty()) {
      throw LoadError(SourceLocation{file->file, 0, 0, std::nullopt, {}, {}},
                      "no o" + label + " sub in this subroutine file (called as o" + label + " call): the file must define it",
                      Error::GcodeSyntax);
    }
    // The subs in line order: the links are, and every sub line has one.
    std::vector<const ControlLink*> defined;
    for (const auto& link : file->structure.links) {
      if (link.keyword == Keyword::Sub) defined.push_back(&link);
    }
    const std::size_t first = defined.front()->line;
    const std::string first_label = label_of_sub(subs, first);
    if (first_label != label) {
      throw LoadError(SourceLocation{file->file, first + 1, 0, std::nullopt, {}, "o" + first_label + " sub"},
                      "the subroutine file of o" + label + " defines o" + first_label + " instead: the sub in " + path.filename().string() +
                          " must be o" + label,
                      Error::GcodeSyntax);
    }
    if (defined.size() > 1) {
      const std::size_t second = defined[1]->line;
      const std::string second_label = label_of_sub(subs, second);
      throw LoadError(SourceLocation{file->file, second + 1, 0, std::nullopt, {}, "o" + second_label + " sub"},
                      "a second subroutine in the file of o" + label + ": a subroutine file holds one sub (LinuxCNC)", Error::GcodeSyntax);
    }
    units_.push_back(std::move(file));
    return SubFile{units_.size() - 1, first};
  }

  /// The label of the sub defined on `line` of a file (its structure's subs).
  static std::string label_of_sub(const std::map<std::string, std::size_t>& subs, std::size_t line) {
    for (const auto& [label, at] : subs) {
      if (at == line) return label;
    }
    return {};
  }

  void return_from(const OWord& oword) {
    if (frames_.size() == 1) fail_oword(oword, "reached without a call", Error::GcodeSyntax);
    const bool has_value = !oword.arguments.empty();
    const double result = has_value ? value(oword.arguments.front()) : 0.0;
    store_.set_named("_value", result);
    store_.set_named("_value_returned", has_value ? 1.0 : 0.0);
    const Frame& frame = frames_.back();
    for (int n = 1; n <= argument_parameters; ++n) store_.set(n, frame.saved[static_cast<std::size_t>(n - 1)]);
    pop_frame();
  }

  ProgramOptions options_;
  std::vector<std::unique_ptr<Unit>> units_;     ///< the program, then each subroutine file read
  std::map<std::string, SubFile> sub_files_;     ///< label -> its subroutine file's sub
  ParameterStore store_;
  std::vector<Frame> frames_;
  std::size_t unit_ = 0;  ///< the file of the program counter
  std::size_t pc_ = 0;
  std::size_t executed_ = 0;
  bool ended_ = false;
};

ProgramReader::ProgramReader(std::string_view text, std::string file_name, ProgramOptions options)
    : impl_(std::make_unique<Impl>(detail::text_lines(text), std::move(file_name), std::move(options))) {}
ProgramReader::ProgramReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ProgramReader ProgramReader::open_file(const std::filesystem::path& path, std::string file_name, ProgramOptions options) {
  options.subroutine_path.insert(options.subroutine_path.begin(), path.parent_path());  // the program's own folder first
  return ProgramReader(std::make_unique<Impl>(detail::file_lines(path), std::move(file_name), std::move(options)));
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
