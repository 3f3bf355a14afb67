#include "tests/fuzz/InputMutator.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace anode::fuzz {

namespace {

bool isNameStart(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == ':';
}
bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '-' ||
         c == '.';
}

struct AttributeSpan {
  size_t begin, end;            // from the space before the name to the closing quote, inclusive
  size_t valueBegin, valueEnd;  // inside the quotes
};

// The attributes of every start tag in `elements`.
std::vector<AttributeSpan> scanAttributes(const std::string& t,
                                          const std::vector<ElementSpan>& elements) {
  std::vector<AttributeSpan> out;
  for (const ElementSpan& e : elements) {
    size_t k = e.nameBegin + e.nameLength;
    while (k < t.size() && t[k] != '>' && t[k] != '/') {
      const size_t start = k;
      while (k < t.size() && std::isspace(static_cast<unsigned char>(t[k]))) ++k;
      if (k == start || k >= t.size() || !isNameStart(t[k])) break;
      while (k < t.size() && isNameChar(t[k])) ++k;
      while (k < t.size() && std::isspace(static_cast<unsigned char>(t[k]))) ++k;
      if (k >= t.size() || t[k] != '=') break;
      ++k;
      while (k < t.size() && std::isspace(static_cast<unsigned char>(t[k]))) ++k;
      if (k >= t.size() || (t[k] != '"' && t[k] != '\'')) break;
      const char quote = t[k];
      const size_t close = t.find(quote, k + 1);
      if (close == std::string::npos) break;
      out.push_back({start, close + 1, k + 1, close});
      k = close + 1;
    }
  }
  return out;
}

struct Span {
  size_t begin, end;
};

// Number tokens outside tag names: [-+]?digits[.digits][e[-+]digits].
std::vector<Span> scanNumbers(const std::string& t) {
  std::vector<Span> out;
  size_t i = 0;
  while (i < t.size()) {
    const char c = t[i];
    const bool sign = (c == '-' || c == '+') && i + 1 < t.size() &&
                      (std::isdigit(static_cast<unsigned char>(t[i + 1])) || t[i + 1] == '.');
    const bool start =
        std::isdigit(static_cast<unsigned char>(c)) || sign ||
        (c == '.' && i + 1 < t.size() && std::isdigit(static_cast<unsigned char>(t[i + 1])));
    if (!start || (i > 0 && (isNameChar(t[i - 1]) && t[i - 1] != '-'))) {
      ++i;
      continue;
    }
    size_t k = i + (sign ? 1 : 0);
    while (k < t.size() && (std::isdigit(static_cast<unsigned char>(t[k])) || t[k] == '.')) ++k;
    if (k < t.size() && (t[k] == 'e' || t[k] == 'E')) {
      size_t m = k + 1;
      if (m < t.size() && (t[m] == '-' || t[m] == '+')) ++m;
      if (m < t.size() && std::isdigit(static_cast<unsigned char>(t[m]))) {
        while (m < t.size() && std::isdigit(static_cast<unsigned char>(t[m]))) ++m;
        k = m;
      }
    }
    out.push_back({i, k});
    i = k;
  }
  return out;
}

// "[...]" lists (no tag inside).
std::vector<Span> scanVectors(const std::string& t) {
  std::vector<Span> out;
  size_t i = 0;
  while ((i = t.find('[', i)) != std::string::npos) {
    const size_t close = t.find(']', i);
    if (close == std::string::npos) break;
    if (t.find('<', i) > close) out.push_back({i, close + 1});
    i = close;
  }
  return out;
}

std::string name(const std::string& t, const ElementSpan& e) {
  return t.substr(e.nameBegin, e.nameLength);
}

std::string shorten(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

const std::vector<std::string> kNumbers = {"1e400",
                                           "-1e400",
                                           "nan",
                                           "NaN",
                                           "-nan",
                                           "inf",
                                           "-inf",
                                           "Infinity",
                                           "-0",
                                           "0",
                                           "-1",
                                           "1e308",
                                           "-1e308",
                                           "1e-320",
                                           "4.9e-324",
                                           "2147483647",
                                           "2147483648",
                                           "-2147483648",
                                           "-2147483649",
                                           "9223372036854775808",
                                           "99999999999999999999",
                                           "1e9",
                                           "1e6",
                                           "1e-9",
                                           "0x10",
                                           "1.",
                                           ".",
                                           "-",
                                           "e5",
                                           "1e",
                                           " ",
                                           "",
                                           "1 2",
                                           "1,2",
                                           "3.0000000000000000001",
                                           "1e+",
                                           "+-1",
                                           "0.5",
                                           "7"};
const std::vector<std::string> kTokens = {"<",
                                          ">",
                                          "</",
                                          "/>",
                                          "<box>",
                                          "</box>",
                                          "]]>",
                                          "<![CDATA[",
                                          "<!--",
                                          "-->",
                                          "&amp;",
                                          "&#0;",
                                          "&#xFFFF;",
                                          "&nosuch;",
                                          "[",
                                          "]",
                                          ",",
                                          "\"",
                                          "'",
                                          "=",
                                          "<?xml version='1.0'?>",
                                          "<Uintah_specification>",
                                          "</Uintah_specification>",
                                          std::string(1, '\0'),
                                          "\xff\xfe",
                                          "\xc3\x28",
                                          "\t",
                                          "\r\n"};
const std::vector<std::string> kAttributeValues = {"",
                                                   "x",
                                                   " ",
                                                   "linear",
                                                   "gimp",
                                                   "cpdi",
                                                   "box",
                                                   "null",
                                                   "common",
                                                   "single_velocity",
                                                   "rf_elastic_plastic",
                                                   "elastic",
                                                   "jg",
                                                   "non_linear1",
                                                   "cubic",
                                                   "constant_rate",
                                                   "Velocity",
                                                   "Dirichlet",
                                                   "Neumann",
                                                   "Symmetric",
                                                   "SD-Type",
                                                   "Concentration",
                                                   "x-",
                                                   "x+",
                                                   "y-",
                                                   "z+",
                                                   "all",
                                                   "0",
                                                   "1",
                                                   "-1",
                                                   "99",
                                                   "2147483648",
                                                   "nan",
                                                   "p.x",
                                                   "p.stress",
                                                   "g.mass",
                                                   "p.concentration",
                                                   "mpm",
                                                   "amrmpm",
                                                   "isotropic_hardening",
                                                   "vonMises",
                                                   "default_hypo",
                                                   "perfect_plasticity",
                                                   "pie_slices",
                                                   "impm",
                                                   "implicit"};
// Values of the ImpMPM tags: negative, zero, huge, not a number, text, empty, and valid ones.
const std::vector<std::string> kImplicitValues = {
    "-1",         "0",           "-0",        "1e300",       "1e400",     "nan",     "inf",
    "2147483648", "-2147483649", "1e-300",    "abc",         "",          "true",    "false",
    "implicit",   "explicit",    "petsc",     "simple",      "0.5",       "1",       "12",
    "25",         "[1,2,3]",     "staggered", "trapezoidal", "cell_mean", "particle"};
const std::vector<std::string> kComponents = {"impm", "mpm", "amrmpm", "implicit", "", "IMPM"};
const std::vector<std::string> kHugeVectors = {"[100000,100000,100000]",
                                               "[2147483647,1,1]",
                                               "[2147483647,2147483647,2147483647]",
                                               "[1290,1290,1290]",
                                               "[46341,46341,1]",
                                               "[1000,1000,1000]",
                                               "[65536,65536,65536]",
                                               "[400,400,400]",
                                               "[-2147483648,1,1]",
                                               "[3000,3000,3000]",
                                               "[100000,1,1]",
                                               "[64,64,64]",
                                               "[0,0,0]"};
const std::vector<std::string> kHugeScalars = {"1000000", "2147483647", "100000", "46341",
                                               "1e9",     "10000",      "-1"};
const std::vector<std::string> kResolutionTags = {"resolution",
                                                  "res",
                                                  "extraCells",
                                                  "patches",
                                                  "num_radial",
                                                  "num_axial",
                                                  "num_angular",
                                                  "periodic",
                                                  "spacing",
                                                  "max_Timesteps",
                                                  "outputTimestepInterval"};
const std::vector<std::string> kVectorReplacements = {"[]",   "[1]",       "[1,2]",   "[1,2,3,4]",
                                                      "[,,]", "[1,,3]",    "[1 2 3]", "[",
                                                      "]",    "[[1,2,3]]", "[1,2,3",  "1,2,3]"};

}  // namespace

std::vector<ElementSpan> scanElements(const std::string& t) {
  std::vector<ElementSpan> out;
  std::vector<size_t> open;
  size_t i = 0;
  while ((i = t.find('<', i)) != std::string::npos) {
    if (t.compare(i, 4, "<!--") == 0) {
      const size_t e = t.find("-->", i + 4);
      if (e == std::string::npos) break;
      i = e + 3;
      continue;
    }
    if (i + 1 < t.size() && (t[i + 1] == '?' || t[i + 1] == '!')) {
      const size_t e = t.find('>', i);
      if (e == std::string::npos) break;
      i = e + 1;
      continue;
    }
    if (i + 1 < t.size() && t[i + 1] == '/') {
      size_t ne = i + 2;
      while (ne < t.size() && isNameChar(t[ne])) ++ne;
      const size_t gt = t.find('>', ne);
      if (gt == std::string::npos || open.empty()) break;
      ElementSpan& e = out[open.back()];
      if (ne - (i + 2) != e.nameLength ||
          t.compare(i + 2, e.nameLength, t, e.nameBegin, e.nameLength) != 0)
        break;
      e.contentEnd = i;
      e.closeNameBegin = i + 2;
      e.end = gt + 1;
      open.pop_back();
      i = gt + 1;
      continue;
    }
    if (i + 1 >= t.size() || !isNameStart(t[i + 1])) {
      ++i;
      continue;
    }
    ElementSpan e;
    e.begin = i;
    e.nameBegin = i + 1;
    size_t k = i + 1;
    while (k < t.size() && isNameChar(t[k])) ++k;
    e.nameLength = k - e.nameBegin;
    char quote = 0;
    for (; k < t.size(); ++k) {
      const char c = t[k];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '>') {
        break;
      }
    }
    if (k >= t.size()) break;
    if (!open.empty()) out[open.back()].leaf = false;
    if (t[k - 1] == '/') {
      e.selfClosing = true;
      e.end = k + 1;
      e.contentBegin = e.contentEnd = k + 1;
    } else {
      e.contentBegin = k + 1;
      open.push_back(out.size());
    }
    out.push_back(e);
    i = k + 1;
  }
  out.erase(std::remove_if(out.begin(), out.end(), [](const ElementSpan& e) { return e.end == 0; }),
            out.end());
  return out;
}

const std::vector<std::string>& implicitTags() {
  static const std::vector<std::string> tags = {"time_integrator",
                                                "dynamic",
                                                "convergence_criteria_disp",
                                                "convergence_criteria_energy",
                                                "iters_before_timestep_restart",
                                                "num_iters_to_decrease_delT",
                                                "num_iters_to_increase_delT",
                                                "delT_decrease_factor",
                                                "delT_increase_factor",
                                                "solver",
                                                "hourglass_stabilization",
                                                "jacobian_coupling_share",
                                                "jacobian_reuse",
                                                "max_concentration_change",
                                                "error_tolerance",
                                                "concentration_coupling",
                                                "diffusion_integrator",
                                                "subcell_concentration_relaxation",
                                                "swelling_strain"};
  return tags;
}

const std::vector<std::string>& surfaceReactionTags() {
  static const std::vector<std::string> tags = {
      "temperature",          "open_circuit_potential", "exchange_flux",
      "transfer_coefficient", "lower_cutoff_potential", "upper_cutoff_potential"};
  return tags;
}

bool editTag(std::string& t, const std::string& parent, const std::string& tag, TagEdit edit,
             const std::string& value) {
  const std::vector<ElementSpan> elements = scanElements(t);
  const ElementSpan* block = nullptr;
  for (const ElementSpan& e : elements)
    if (!e.selfClosing && name(t, e) == parent) {
      block = &e;
      break;
    }
  if (!block) return false;
  // The <tag> children of the block (a leaf or self-closing element directly inside it).
  std::vector<ElementSpan> found;
  for (const ElementSpan& e : elements)
    if (e.begin >= block->contentBegin && e.end <= block->contentEnd && name(t, e) == tag)
      found.push_back(e);
  const std::string element = "<" + tag + ">" + value + "</" + tag + ">";
  switch (edit) {
    case TagEdit::Set:
      if (found.empty())
        t.insert(block->contentBegin, element);
      else
        t.replace(found[0].begin, found[0].end - found[0].begin, element);
      return true;
    case TagEdit::Remove:
      if (found.empty()) return false;
      for (auto e = found.rbegin(); e != found.rend(); ++e) t.erase(e->begin, e->end - e->begin);
      return true;
    case TagEdit::Duplicate:
      if (found.empty()) return false;
      t.insert(found[0].end, t.substr(found[0].begin, found[0].end - found[0].begin));
      return true;
  }
  return false;
}

const char* InputMutator::operatorName(int op) {
  static const char* names[] = {
      "flip-bit",       "replace-byte",     "insert-token",        "delete-bytes",
      "truncate",       "delete-element",   "duplicate-element",   "move-element",
      "rename-element", "delete-attribute", "duplicate-attribute", "corrupt-attribute",
      "corrupt-number", "huge-resolution",  "vector-length",       "swap-values",
      "empty-value",    "implicit-option"};
  static_assert(sizeof(names) / sizeof(names[0]) == kOperatorCount, "a name per operator");
  return op >= 0 && op < kOperatorCount ? names[op] : "?";
}

bool InputMutator::apply(int op, std::string& t, std::string* what) {
  char buffer[256];
  auto say = [&](const std::string& s) {
    if (what) *what = std::string(operatorName(op)) + ": " + s;
  };
  if (t.empty()) return false;
  switch (op) {
    case FlipBit: {
      const size_t pos = pick(t.size());
      const int bit = static_cast<int>(pick(8));
      t[pos] = static_cast<char>(t[pos] ^ (1 << bit));
      std::snprintf(buffer, sizeof buffer, "bit %d of byte %zu", bit, pos);
      say(buffer);
      return true;
    }
    case ReplaceByte: {
      static const std::string bytes =
          std::string("<>/\"'[],-+.0123456789eE =&;!?x\n") + std::string(1, '\0') + "\x7f\x80\xff";
      const size_t pos = pick(t.size());
      const char c = bytes[pick(bytes.size())];
      t[pos] = c;
      std::snprintf(buffer, sizeof buffer, "byte %zu set to 0x%02x", pos,
                    static_cast<unsigned char>(c));
      say(buffer);
      return true;
    }
    case InsertToken: {
      const size_t pos = pick(t.size() + 1);
      const std::string& token = pickFrom(kTokens);
      t.insert(pos, token);
      std::snprintf(buffer, sizeof buffer, "at byte %zu", pos);
      say(std::string(buffer) + " '" + shorten(token) + "'");
      return true;
    }
    case DeleteBytes: {
      const size_t pos = pick(t.size());
      const size_t n = 1 + pick(std::min<size_t>(64, t.size() - pos));
      t.erase(pos, n);
      std::snprintf(buffer, sizeof buffer, "%zu bytes at %zu", n, pos);
      say(buffer);
      return true;
    }
    case Truncate: {
      const size_t pos = pick(t.size());
      t.resize(pos);
      std::snprintf(buffer, sizeof buffer, "at byte %zu", pos);
      say(buffer);
      return true;
    }
    default:
      break;
  }

  const std::vector<ElementSpan> elements = scanElements(t);
  // The first element (the root) is left alone by the structural operators.
  const std::vector<ElementSpan> inner(elements.size() > 1 ? elements.begin() + 1 : elements.end(),
                                       elements.end());
  std::vector<ElementSpan> leaves;
  for (const ElementSpan& e : inner)
    if (e.leaf && !e.selfClosing) leaves.push_back(e);

  switch (op) {
    case DeleteElement: {
      if (inner.empty()) return false;
      const ElementSpan& e = pickFrom(inner);
      say("<" + name(t, e) + "> at byte " + std::to_string(e.begin));
      t.erase(e.begin, e.end - e.begin);
      return true;
    }
    case DuplicateElement: {
      if (inner.empty()) return false;
      const ElementSpan& e = pickFrom(inner);
      say("<" + name(t, e) + "> at byte " + std::to_string(e.begin));
      t.insert(e.end, t.substr(e.begin, e.end - e.begin));
      return true;
    }
    case MoveElement: {
      if (inner.size() < 2) return false;
      const ElementSpan& e = pickFrom(inner);
      std::vector<ElementSpan> targets;
      for (const ElementSpan& d : elements)
        if (!d.selfClosing && (d.contentBegin <= e.begin || d.contentBegin >= e.end))
          targets.push_back(d);
      if (targets.empty()) return false;
      const ElementSpan& d = pickFrom(targets);
      const std::string moved = t.substr(e.begin, e.end - e.begin);
      say("<" + name(t, e) + "> into <" + name(t, d) + ">");
      size_t at = d.contentBegin;
      t.erase(e.begin, e.end - e.begin);
      if (at >= e.end) at -= e.end - e.begin;
      t.insert(at, moved);
      return true;
    }
    case RenameElement: {
      if (inner.empty()) return false;
      const ElementSpan& e = pickFrom(inner);
      const std::string to = name(t, pickFrom(elements));
      say("<" + name(t, e) + "> to <" + to + ">");
      if (!e.selfClosing) t.replace(e.closeNameBegin, e.nameLength, to);
      t.replace(e.nameBegin, e.nameLength, to);
      return true;
    }
    case DeleteAttribute:
    case DuplicateAttribute:
    case CorruptAttribute: {
      const std::vector<AttributeSpan> attributes = scanAttributes(t, elements);
      if (attributes.empty()) return false;
      const AttributeSpan& a = pickFrom(attributes);
      const std::string text = t.substr(a.begin, a.end - a.begin);
      if (op == DeleteAttribute) {
        say("'" + shorten(text) + "'");
        t.erase(a.begin, a.end - a.begin);
      } else if (op == DuplicateAttribute) {
        say("'" + shorten(text) + "'");
        t.insert(a.end, text);
      } else {
        const std::string& v = pickFrom(kAttributeValues);
        say("'" + shorten(text) + "' value to '" + v + "'");
        t.replace(a.valueBegin, a.valueEnd - a.valueBegin, v);
      }
      return true;
    }
    case CorruptNumber: {
      const std::vector<Span> numbers = scanNumbers(t);
      if (numbers.empty()) return false;
      const Span& s = pickFrom(numbers);
      const std::string old = t.substr(s.begin, s.end - s.begin);
      std::string v;
      if (pick(3) == 0) {
        // Scaled by a power of ten, possibly negated: plausible but out-of-range values.
        const double x = std::strtod(old.c_str(), nullptr);
        const int exponent = static_cast<int>(pick(25)) - 12;
        std::snprintf(buffer, sizeof buffer, "%.17g",
                      (pick(2) ? -1 : 1) * x * std::pow(10.0, exponent));
        v = buffer;
      } else {
        v = pickFrom(kNumbers);
      }
      say("'" + old + "' at byte " + std::to_string(s.begin) + " to '" + v + "'");
      t.replace(s.begin, s.end - s.begin, v);
      return true;
    }
    case HugeResolution: {
      std::vector<ElementSpan> sized;
      for (const ElementSpan& e : leaves)
        if (std::find(kResolutionTags.begin(), kResolutionTags.end(), name(t, e)) !=
            kResolutionTags.end())
          sized.push_back(e);
      if (sized.empty()) return false;
      const ElementSpan& e = pickFrom(sized);
      const bool vector =
          t.substr(e.contentBegin, e.contentEnd - e.contentBegin).find('[') != std::string::npos;
      const std::string& v = vector ? pickFrom(kHugeVectors) : pickFrom(kHugeScalars);
      say("<" + name(t, e) + "> to " + v);
      t.replace(e.contentBegin, e.contentEnd - e.contentBegin, v);
      return true;
    }
    case VectorLength: {
      const std::vector<Span> vectors = scanVectors(t);
      if (vectors.empty()) return false;
      const Span& s = pickFrom(vectors);
      const std::string old = t.substr(s.begin, s.end - s.begin);
      std::string v;
      const size_t choice = pick(3);
      if (choice == 0) {  // one component fewer
        const size_t comma = old.rfind(',');
        v = comma == std::string::npos ? "[]" : old.substr(0, comma) + "]";
      } else if (choice == 1) {  // one more
        v = old.substr(0, old.size() - 1) + ", " + old.substr(1, old.find_first_of(",]") - 1) + "]";
      } else {
        v = pickFrom(kVectorReplacements);
      }
      say("'" + shorten(old) + "' to '" + shorten(v) + "'");
      t.replace(s.begin, s.end - s.begin, v);
      return true;
    }
    case SwapValues: {
      if (leaves.size() < 2) return false;
      const ElementSpan& a = pickFrom(leaves);
      const ElementSpan& b = pickFrom(leaves);
      if (a.begin == b.begin) return false;
      const ElementSpan& first = a.begin < b.begin ? a : b;
      const ElementSpan& second = a.begin < b.begin ? b : a;
      const std::string va = t.substr(first.contentBegin, first.contentEnd - first.contentBegin);
      const std::string vb = t.substr(second.contentBegin, second.contentEnd - second.contentBegin);
      say("<" + name(t, first) + "> '" + shorten(va) + "' and <" + name(t, second) + "> '" +
          shorten(vb) + "'");
      t.replace(second.contentBegin, vb.size(), va);
      t.replace(first.contentBegin, va.size(), vb);
      return true;
    }
    case EmptyValue: {
      if (leaves.empty()) return false;
      const ElementSpan& e = pickFrom(leaves);
      say("<" + name(t, e) + ">");
      t.erase(e.contentBegin, e.contentEnd - e.contentBegin);
      return true;
    }
    case ImplicitOption: {
      if (pick(8) == 0) {
        const std::string key = "<SimulationComponent type=\"";
        const size_t at = t.find(key);
        if (at == std::string::npos) return false;
        const size_t end = t.find('"', at + key.size());
        if (end == std::string::npos) return false;
        const std::string& v = pickFrom(kComponents);
        say("<SimulationComponent> type to '" + v + "'");
        t.replace(at + key.size(), end - at - key.size(), v);
        return true;
      }
      if (pick(8) == 0) {  // ours in <DataArchiver>: the film's normal
        static const std::vector<std::string> normals = {"z", "x", "w", "", "[0,0,1]", "zz"};
        const std::string& v = pickFrom(normals);
        if (!editTag(t, "DataArchiver", "film_normal", TagEdit::Set, v)) return false;
        say("<film_normal> set to '" + v + "'");
        return true;
      }
      if (pick(8) ==
          0) {  // ours in <constitutive_model>: lithium-dependent laws, rate-dependent flow
        static const std::vector<std::string> tags = {
            "bulk_modulus_lithiated", "shear_modulus_lithiated", "sigma_Y_lithiated",
            "reference_strain_rate", "rate_exponent"};
        static const std::vector<std::string> values = {"1e6", "0",   "-1",     "nan",  "inf",
                                                        "",    "abc", "1e-300", "1e300"};
        const std::string& tag = pickFrom(tags);
        const std::string& v = pickFrom(values);
        const bool flowTag = tag.find("modulus") == std::string::npos;
        if (!editTag(t, flowTag ? "flow_model" : "constitutive_model", tag, TagEdit::Set, v))
          return false;
        say("<" + tag + "> set to '" + v + "'");
        return true;
      }
      if (pick(8) == 0) {  // ours: a galvanostatic <scalar_flux>'s <surface_reaction>
        const std::string& tag = pickFrom(surfaceReactionTags());
        static const std::vector<std::string> values = {"0.4", "0",   "-1", "nan",  "inf",
                                                        "",    "abc", "1",  "1e300"};
        const std::string& v = pickFrom(values);
        if (!editTag(t, "surface_reaction", tag, TagEdit::Set, v)) return false;
        say("<" + tag + "> set to '" + v + "'");
        return true;
      }
      if (pick(8) ==
          0) {  // ours: stress-driven diffusion, <diffusion_model type=chemical_potential>
        const std::string key = "<diffusion_model type=\"";
        const size_t at = t.find(key);
        if (at == std::string::npos) return false;
        const size_t end = t.find('"', at + key.size());
        if (end == std::string::npos) return false;
        t.replace(at + key.size(), end - at - key.size(), "chemical_potential");
        static const std::vector<std::string> values = {"7.7e5", "1", "0",   "-1",    "nan",
                                                        "inf",   "",  "abc", "1e-300"};
        const std::string& v = pickFrom(values);
        const std::string tag = pick(3) == 0 ? "stress_coupling" : "cmax_RT";
        if (tag == "stress_coupling") editTag(t, "diffusion_model", "cmax_RT", TagEdit::Set, "1e6");
        if (!editTag(t, "diffusion_model", tag, TagEdit::Set, v)) return false;
        say("<diffusion_model> type to 'chemical_potential', <" + tag + "> set to '" + v + "'");
        return true;
      }
      const std::string& tag = pickFrom(implicitTags());
      const size_t choice = pick(4);
      if (choice == 1 && editTag(t, "MPM", tag, TagEdit::Remove)) {
        say("<" + tag + "> removed");
        return true;
      }
      if (choice == 2 && editTag(t, "MPM", tag, TagEdit::Duplicate)) {
        say("<" + tag + "> duplicated");
        return true;
      }
      const std::string& v = pickFrom(kImplicitValues);
      if (!editTag(t, "MPM", tag, TagEdit::Set, v)) return false;
      say("<" + tag + "> set to '" + shorten(v) + "'");
      return true;
    }
    default:
      return false;
  }
}

std::string InputMutator::mutate(std::string& text, std::vector<int>* operatorsUsed) {
  // Byte-level operators break the XML almost always; structural and value operators reach the
  // validation behind the parser, so they are drawn more often.
  static const int weights[kOperatorCount] = {2, 2, 2, 2, 1, 4, 4, 3, 3, 2, 2, 4, 8, 4, 4, 4, 3, 3};
  std::discrete_distribution<int> choose(std::begin(weights), std::end(weights));
  const int count = 1 + static_cast<int>(pick(3));
  std::string description;
  for (int applied = 0, attempts = 0; applied < count && attempts < 20; ++attempts) {
    const int op = choose(rng_);
    std::string what;
    if (!apply(op, text, &what)) continue;
    ++applied;
    if (operatorsUsed) operatorsUsed->push_back(op);
    description += (description.empty() ? "" : "; ") + what;
  }
  return description;
}

}  // namespace anode::fuzz
