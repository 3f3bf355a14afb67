#include "Core/ProblemSpec/ProblemSpec.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace anode {

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

double parseDouble(const std::string& raw) {
  const std::string s = trim(raw);
  if (s.empty()) throw std::invalid_argument("expected a number, found nothing");
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size())
    throw std::invalid_argument("expected a number, found '" + s + "'");
  // strtod reads "nan", "inf" and overflows to infinity: no input quantity may be either.
  if (!std::isfinite(v)) throw std::invalid_argument("expected a finite number, found '" + s + "'");
  return v;
}

int parseInt(const std::string& raw) {
  const std::string s = trim(raw);
  if (s.empty()) throw std::invalid_argument("expected an integer, found nothing");
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (end != s.c_str() + s.size())
    throw std::invalid_argument("expected an integer, found '" + s + "'");
  if (v < -2147483647L || v > 2147483647L)
    throw std::invalid_argument("integer out of range: " + s);
  return static_cast<int>(v);
}

// "[a, b, ...]" -> its fields.
std::vector<std::string> splitList(const std::string& raw) {
  const std::string s = trim(raw);
  if (s.size() < 2 || s.front() != '[' || s.back() != ']')
    throw std::invalid_argument("expected a list [a, b, ...], found '" + s + "'");
  std::vector<std::string> fields;
  std::stringstream in(s.substr(1, s.size() - 2));
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

// "[a, b, c]" -> three fields.
std::vector<std::string> splitVector(const std::string& raw) {
  const std::string s = trim(raw);
  const auto fields = splitList(s);
  if (fields.size() != 3)
    throw std::invalid_argument("expected a vector of 3 components [a, b, c], found '" + s + "'");
  return fields;
}

}  // namespace

template <>
double parseValue<double>(const std::string& text) {
  return parseDouble(text);
}
template <>
int parseValue<int>(const std::string& text) {
  return parseInt(text);
}
template <>
std::string parseValue<std::string>(const std::string& text) {
  return trim(text);
}
template <>
bool parseValue<bool>(const std::string& text) {
  std::string s = trim(text);
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  if (s == "true") return true;
  if (s == "false") return false;
  throw std::invalid_argument("expected true or false, found '" + trim(text) + "'");
}
template <>
Vec3 parseValue<Vec3>(const std::string& text) {
  const auto f = splitVector(text);
  return Vec3(parseDouble(f[0]), parseDouble(f[1]), parseDouble(f[2]));
}
template <>
Vec3i parseValue<Vec3i>(const std::string& text) {
  const auto f = splitVector(text);
  return Vec3i(parseInt(f[0]), parseInt(f[1]), parseInt(f[2]));
}

template <>
std::vector<int> parseValue<std::vector<int>>(const std::string& text) {
  std::vector<int> out;
  for (const auto& f : splitList(text)) out.push_back(parseInt(f));
  return out;
}

// ---- PSNode ----

std::string PSNode::name() const {
  return e_ ? e_->Name() : "";
}
int PSNode::line() const {
  return e_ ? e_->GetLineNum() : 0;
}
const std::string& PSNode::file() const {
  return spec_->file();
}

PSNode PSNode::child(const char* tag) const {
  const tinyxml2::XMLElement* c = e_->FirstChildElement(tag);
  if (c) spec_->markUsed(c);
  return PSNode(c, spec_);
}

namespace {

// The number of single-character insertions, deletions and substitutions turning a into b.
size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// A tag this many edits from a required one may be it misspelt.
constexpr size_t kMisspelling = 2;

// Tags that differ only in their digits (<tuning1>, <tuning2>) are a family, not misspellings.
std::string withoutDigits(std::string tag) {
  tag.erase(std::remove_if(tag.begin(), tag.end(), [](char c) { return std::isdigit(c) != 0; }),
            tag.end());
  return tag;
}

}  // namespace

PSNode PSNode::requireChild(const char* tag) const {
  PSNode c = child(tag);
  if (c) return c;
  std::string message = "<" + name() + "> requires a <" + std::string(tag) + "> tag";
  // A child nothing has read so far whose tag is close to the required one: named as a likely
  // misspelling (it may yet be read later, so this is a question, not a verdict).
  for (const auto* e = e_->FirstChildElement(); e; e = e->NextSiblingElement())
    if (!spec_->isUsed(e) && editDistance(e->Name(), tag) <= kMisspelling &&
        withoutDigits(e->Name()) != withoutDigits(tag)) {
      message +=
          " (line " + std::to_string(e->GetLineNum()) + " has <" + e->Name() + ">: misspelt?)";
      break;
    }
  fail(message);
}

void PSNode::requireEverythingRead() const {
  for (const auto* e = e_->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (!spec_->isUsed(e))
      throw InputError(file(), e->GetLineNum(),
                       "unknown tag <" + std::string(e->Name()) + "> in <" + name() + ">");
    PSNode(e, spec_).requireEverythingRead();
  }
}

std::vector<PSNode> PSNode::children(const char* tag) const {
  std::vector<PSNode> out;
  for (const auto* c = e_->FirstChildElement(tag); c; c = c->NextSiblingElement(tag)) {
    spec_->markUsed(c);
    out.emplace_back(c, spec_);
  }
  return out;
}

std::vector<PSNode> PSNode::childrenWhere(bool (*select)(const std::string& tag)) const {
  std::vector<PSNode> out;
  for (const auto* c = e_->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (!select(c->Name())) continue;
    spec_->markUsed(c);
    out.emplace_back(c, spec_);
  }
  return out;
}

bool PSNode::hasChildren() const {
  return e_->FirstChildElement() != nullptr;
}

std::string PSNode::text() const {
  // Concatenate all text children: comments may sit between pieces of a value.
  std::string s;
  for (const auto* n = e_->FirstChild(); n; n = n->NextSibling())
    if (const auto* t = n->ToText()) s += t->Value();
  return s;
}

template <class T>
T PSNode::value() const {
  try {
    return parseValue<T>(text());
  } catch (const std::invalid_argument& err) {
    fail("<" + name() + ">: " + err.what());
  }
}

template <class T>
std::optional<T> PSNode::find(const char* tag) const {
  const PSNode c = child(tag);
  if (!c) return std::nullopt;
  return c.value<T>();
}

template <class T>
T PSNode::require(const char* tag) const {
  return requireChild(tag).value<T>();
}

template <class T>
T PSNode::get(const char* tag, const T& fallback) const {
  return find<T>(tag).value_or(fallback);
}

std::optional<std::string> PSNode::attribute(const char* attr) const {
  const char* v = e_->Attribute(attr);
  if (!v) return std::nullopt;
  return trim(v);
}

std::vector<std::string> PSNode::attributeNames() const {
  std::vector<std::string> names;
  for (const tinyxml2::XMLAttribute* a = e_->FirstAttribute(); a; a = a->Next())
    names.push_back(a->Name());
  return names;
}

std::string PSNode::requireAttribute(const char* attr) const {
  auto v = attribute(attr);
  if (!v) fail("<" + name() + "> requires the attribute " + attr + "=\"...\"");
  return *v;
}

void PSNode::acceptInert(const char* tag) const {
  for (const auto& c : children(tag)) c.markSubtreeUsed();
}

void PSNode::markSubtreeUsed() const {
  std::function<void(const tinyxml2::XMLElement*)> mark = [&](const tinyxml2::XMLElement* e) {
    spec_->markUsed(e);
    for (const auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) mark(c);
  };
  mark(e_);
}

void PSNode::fail(const std::string& message) const {
  throw InputError(file(), line(), message);
}

void PSNode::warn(const std::string& message) const {
  spec_->warn(file() + ":" + std::to_string(line()) + ": " + message);
}

void PSNode::unsupported(const std::string& message) const {
  if (!spec_->ignoreUnsupported())
    fail(message + " (not supported; --ignore-unsupported runs without it)");
  warn(message + " (not supported; ignored because of --ignore-unsupported)");
}

template double PSNode::value<double>() const;
template int PSNode::value<int>() const;
template bool PSNode::value<bool>() const;
template std::string PSNode::value<std::string>() const;
template Vec3 PSNode::value<Vec3>() const;
template Vec3i PSNode::value<Vec3i>() const;
template std::vector<int> PSNode::value<std::vector<int>>() const;
#define ANODE_INSTANTIATE(T)                              \
  template T PSNode::require<T>(const char*) const;       \
  template T PSNode::get<T>(const char*, const T&) const; \
  template std::optional<T> PSNode::find<T>(const char*) const;
ANODE_INSTANTIATE(double)
ANODE_INSTANTIATE(int)
ANODE_INSTANTIATE(bool)
ANODE_INSTANTIATE(std::string)
ANODE_INSTANTIATE(Vec3)
ANODE_INSTANTIATE(Vec3i)
ANODE_INSTANTIATE(std::vector<int>)
#undef ANODE_INSTANTIATE

// ---- ProblemSpec ----

ProblemSpec::ProblemSpec(const std::string& name, bool ignoreUnsupported, int)
    : file_(name), ignoreUnsupported_(ignoreUnsupported) {}

ProblemSpec::ProblemSpec(const std::string& file, bool ignoreUnsupported, const char* rootName)
    : ProblemSpec(file, ignoreUnsupported, 0) {
  std::ifstream probe(file);
  if (!probe) throw InputError(file, 0, "cannot open the input file");
  parse(doc_.LoadFile(file.c_str()), rootName);
}

std::unique_ptr<ProblemSpec> ProblemSpec::fromText(const std::string& text, const std::string& name,
                                                   bool ignoreUnsupported) {
  std::unique_ptr<ProblemSpec> spec(new ProblemSpec(name, ignoreUnsupported, 0));
  spec->parse(spec->doc_.Parse(text.c_str(), text.size()), "Uintah_specification");
  return spec;
}

void ProblemSpec::parse(tinyxml2::XMLError status, const char* rootName) {
  if (status == tinyxml2::XML_ERROR_EMPTY_DOCUMENT)
    throw InputError(file_, 1, "the input is empty: no XML element");
  if (status != tinyxml2::XML_SUCCESS) {
    const char* what = doc_.ErrorStr();
    // tinyxml2 reports line 0 for errors it cannot place; every message names a line of the file.
    throw InputError(file_, std::max(1, doc_.ErrorLineNum()),
                     std::string("malformed XML: ") + (what ? what : "parse error"));
  }
  const auto* r = doc_.RootElement();
  if (!r) throw InputError(file_, 1, "the input holds no XML element");
  if (std::string(r->Name()) != rootName)
    throw InputError(file_, r->GetLineNum(),
                     "the root element must be <" + std::string(rootName) + ">, found <" +
                         std::string(r->Name()) + ">");
}

PSNode ProblemSpec::root() {
  auto* r = doc_.RootElement();
  markUsed(r);
  return PSNode(r, this);
}

void ProblemSpec::checkAllUsed() const {
  std::vector<std::pair<int, std::string>> unknown;
  std::function<void(const tinyxml2::XMLElement*, const std::string&)> walk =
      [&](const tinyxml2::XMLElement* e, const std::string& parent) {
        if (!used_.count(e)) {
          unknown.emplace_back(e->GetLineNum(),
                               "unknown tag <" + std::string(e->Name()) + "> in <" + parent + ">");
          return;  // its children are unknown by extension
        }
        for (const auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
          walk(c, e->Name());
      };
  walk(doc_.RootElement(), "");
  if (unknown.empty()) return;
  std::string message = unknown.front().second;
  for (size_t i = 1; i < unknown.size(); ++i)
    message += "\n" + file_ + ":" + std::to_string(unknown[i].first) + ": " + unknown[i].second;
  throw InputError(file_, unknown.front().first, message);
}

}  // namespace anode
