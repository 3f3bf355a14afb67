// Reader for Uintah-style .ups inputs. Every tag that setup reads is marked as used; after setup,
// checkAllUsed() names each tag nobody read, so a misspelt or unknown tag is never silently
// ignored.
#pragma once

#include <tinyxml2.h>

#include <memory>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "Core/Math/Types.h"
#include "Core/Util/Errors.h"

namespace anode {

class ProblemSpec;

// A view of one element of the input. Cheap to copy; valid while its ProblemSpec lives.
class PSNode {
 public:
  PSNode() = default;
  PSNode(const tinyxml2::XMLElement* element, ProblemSpec* spec) : e_(element), spec_(spec) {}

  explicit operator bool() const { return e_ != nullptr; }
  std::string name() const;
  int line() const;
  const std::string& file() const;

  // Optional child (the first with that name); an empty node if absent. Marks it used.
  PSNode child(const char* tag) const;
  // Required child; an error naming this element's line if absent.
  PSNode requireChild(const char* tag) const;
  // All children with that name (all element children when tag is null). Marks them used.
  std::vector<PSNode> children(const char* tag = nullptr) const;
  // The element children whose tag `select` accepts, in document order. Marks only those, so
  // an unknown tag among the others is still reported by checkAllUsed().
  std::vector<PSNode> childrenWhere(bool (*select)(const std::string& tag)) const;
  // Whether this element has any element child. Marks nothing.
  bool hasChildren() const;

  // Typed value of a child tag: T is double, int, bool, std::string, Vec3, Vec3i or
  // std::vector<int> (a list "[a, b, ...]").
  template <class T>
  T require(const char* tag) const;
  template <class T>
  T get(const char* tag, const T& fallback) const;
  template <class T>
  std::optional<T> find(const char* tag) const;
  // Typed value of this element's own text.
  template <class T>
  T value() const;

  std::string text() const;
  std::optional<std::string> attribute(const char* name) const;
  std::string requireAttribute(const char* name) const;
  // The names of this element's attributes, in document order.
  std::vector<std::string> attributeNames() const;

  // Accept a child tag (and everything inside it) that changes nothing in this code.
  void acceptInert(const char* tag) const;
  // Mark this element and everything inside it as read.
  void markSubtreeUsed() const;
  // For an element whose reading is complete: an error naming the first element inside it that
  // nothing has read (as checkAllUsed() would after setup), so that a check depending on the
  // element is not the first error a misspelt tag in it gives.
  void requireEverythingRead() const;

  [[noreturn]] void fail(const std::string& message) const;
  // A feature the input asks for but this code does not support: an error, or a warning when the
  // run was started with --ignore-unsupported.
  void unsupported(const std::string& message) const;
  // A warning naming this element's line, printed before the run starts.
  void warn(const std::string& message) const;

 private:
  const tinyxml2::XMLElement* e_ = nullptr;
  ProblemSpec* spec_ = nullptr;
};

class ProblemSpec {
 public:
  // Parses the file; broken XML is an InputError with the line tinyxml2 reports, and so is a
  // root element of another name (an input's is <Uintah_specification>).
  ProblemSpec(const std::string& file, bool ignoreUnsupported,
              const char* rootName = "Uintah_specification");
  // Parses text held in memory; `name` stands for the file name in messages.
  static std::unique_ptr<ProblemSpec> fromText(const std::string& text, const std::string& name,
                                               bool ignoreUnsupported = false);

  PSNode root();
  const std::string& file() const { return file_; }
  bool ignoreUnsupported() const { return ignoreUnsupported_; }
  const std::vector<std::string>& warnings() const { return warnings_; }

  void markUsed(const tinyxml2::XMLElement* e) { used_.insert(e); }
  bool isUsed(const tinyxml2::XMLElement* e) const { return used_.count(e) != 0; }
  void warn(const std::string& message) { warnings_.push_back(message); }
  // Throws an InputError naming every element that no part of setup read.
  void checkAllUsed() const;

 private:
  ProblemSpec(const std::string& name, bool ignoreUnsupported, int);
  void parse(tinyxml2::XMLError status, const char* rootName);

  std::string file_;
  bool ignoreUnsupported_;
  tinyxml2::XMLDocument doc_;
  std::unordered_set<const tinyxml2::XMLElement*> used_;
  std::vector<std::string> warnings_;
};

// Parsing of one value from text; throws std::invalid_argument with what was expected.
template <class T>
T parseValue(const std::string& text);

}  // namespace anode
