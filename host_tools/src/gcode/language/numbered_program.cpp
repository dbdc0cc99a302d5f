// SPDX-License-Identifier: MIT
#include "numbered_program.hpp"

#include <algorithm>
#include <cmath>

#include <curvestep/host/csv.hpp>

namespace curvestep::host::gcode::detail {
namespace {

/// A G code that reads P or L (dwell, G10, arcs' turns, splines, G64, cycles): beside M98 it would take M98's.
bool takes_p_or_l(const Node& g) {
  if (g.kind != NodeKind::Number) return false;
  const double code = g.number;
  return code == 2 || code == 3 || code == 4 || code == 5 || code == 5.1 || code == 5.2 || code == 10 || code == 64 || code == 73 ||
         code == 76 || (code >= 81 && code <= 89);
}

/// Word `word` (value `number`) as a whole number (whole_number), or a LineError saying what it must be.
long long whole_word(const WordValue& word, double number, double limit, double tolerance, const std::string& what) {
  const auto whole = whole_number(number, limit, tolerance);
  if (!whole) {
    throw LineError(word.column, std::string(1, word.letter), what + " (" + format_number(number) + " given)", Error::GcodeBadNumber);
  }
  return *whole;
}

}  // namespace

std::optional<long long> whole_number(double number, double limit, double tolerance) {
  const double nearest = std::floor(number + 0.5);
  if (!(nearest >= 0.0 && nearest < limit && std::fabs(number - nearest) <= tolerance)) return std::nullopt;
  return static_cast<long long>(nearest);
}

NumberedCall numbered_call(const ParsedLine& line, const WordValue& m98, const std::function<double(NodeIndex)>& value,
                           const ProgramStructure& structure, const std::string& file, double max_passes) {
  for (const auto& word : line.words) {
    if (word.letter == 'G' && takes_p_or_l(line.nodes[word.value])) {
      throw LineError(word.column, "G", "M98 takes the line's P and L: put this G code on a line of its own", Error::GcodeConflictingWords);
    }
  }
  const WordValue* p = word_of(line, 'P');
  if (!p) throw LineError(m98.column, "M98", "M98 needs P, the number of the program it calls: M98 P100 [L passes]", Error::GcodeSyntax);
  const std::string label =
      std::to_string(whole_word(*p, value(p->value), max_label, 1e-4, "M98 P, a program number, is a whole number 0..999999999"));
  const WordValue* l = word_of(line, 'L');
  const long long passes = l ? whole_word(*l, value(l->value), max_passes, 0.5, "M98 L, a count of passes, is 0..10^15") : 1;
  const auto found = structure.numbered.find(label);
  if (found != structure.numbered.end()) return NumberedCall{found->second, passes};
  if (structure.subs.count(label) != 0) {
    throw LineError(m98.column, "M98", "o" + label + " is a sub (o" + label + " sub ... endsub): call it with o" + label +
                                           " call; M98 calls a numbered program (O" + label + " ... M99)",
                    Error::GcodeSyntax);
  }
  throw LineError(p->column, "P", "no numbered program O" + label + " (O" + label + " ... M99) in " + file + " for M98 to call",
                  Error::GcodeSyntax);
}

void fail_main_program_m99(const ProgramStructure& structure, const WordValue& m99) {
  std::string hint;
  const auto number = std::find_if(structure.links.begin(), structure.links.end(),
                                   [](const ControlLink& l) { return l.keyword == Keyword::Program && !l.m99 && l.closing == no_line; });
  if (number != structure.links.end()) {
    hint = " (the O-word on line " + std::to_string(number->line + 1) +
           " is the program's number: a program ending with M99 is a subprogram, which M98 calls from a main program "
           "before it in the same file; run on its own, it ends with M2 or M30)";
  }
  throw LineError(m99.column, "M99",
                  "M99 in the main program restarts it without end (LinuxCNC's endless program): a job must end; end it with M2 or M30" + hint,
                  Error::GcodeSyntax);
}

}  // namespace curvestep::host::gcode::detail
