// Mutations of a .ups text for fuzzing the input reader: byte flips, truncation, element and
// attribute deletion/duplication, corrupted numbers ("1e400", "nan", "-0", ...), huge
// resolutions, vectors of the wrong length, values swapped between tags. Deterministic for a seed.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace anode::fuzz {

// One element of the text as the mutator sees it (a tolerant scan, not an XML parser).
struct ElementSpan {
  size_t begin = 0, end = 0;                // the whole element, [begin, end)
  size_t nameBegin = 0, nameLength = 0;     // the tag name in the start tag
  size_t contentBegin = 0, contentEnd = 0;  // between start and end tag (empty if self-closing)
  size_t closeNameBegin = 0;                // the name in the end tag (0 if self-closing)
  bool selfClosing = false;
  bool leaf = true;  // no child element
};

// The elements of `text`, in document order; comments and declarations are skipped. Unbalanced
// tags end the scan (what was matched so far is returned).
std::vector<ElementSpan> scanElements(const std::string& text);

// The ImpMPM tags of <MPM> (docs/quasi-static.md) the implicit-option operator edits.
const std::vector<std::string>& implicitTags();
// The tags of a galvanostatic <scalar_flux>'s <surface_reaction> (ours).
const std::vector<std::string>& surfaceReactionTags();

enum class TagEdit { Set, Remove, Duplicate };
// Edits <tag> in the first <parent> element (not self-closing) of `text`: Set gives it `value`
// (inserting it first in <parent> when absent), Remove deletes every <tag> there, Duplicate
// repeats the first one. Returns false, text unchanged, when there is no <parent>, or no <tag> to
// remove or duplicate.
bool editTag(std::string& text, const std::string& parent, const std::string& tag, TagEdit edit,
             const std::string& value = "");

class InputMutator {
 public:
  enum Operator {
    FlipBit,
    ReplaceByte,
    InsertToken,
    DeleteBytes,
    Truncate,
    DeleteElement,
    DuplicateElement,
    MoveElement,
    RenameElement,
    DeleteAttribute,
    DuplicateAttribute,
    CorruptAttribute,
    CorruptNumber,
    HugeResolution,
    VectorLength,
    SwapValues,
    EmptyValue,
    ImplicitOption,  // an ImpMPM tag of <MPM> (or ours: <DataArchiver><film_normal>, the
                     // lithium-dependent laws' tags, chemical_potential's, <surface_reaction>'s)
                     // set to a bad value,
                     // removed or duplicated, or the <SimulationComponent> type changed
    kOperatorCount
  };
  static const char* operatorName(int op);

  explicit InputMutator(uint64_t seed) : rng_(seed) {}

  // Applies one operator; returns false (text unchanged) when the text offers it nothing to work
  // on. `what` receives a one-line description of the change.
  bool apply(int op, std::string& text, std::string* what);
  // Applies 1 to 3 random operators; returns the descriptions joined with "; ".
  std::string mutate(std::string& text, std::vector<int>* operatorsUsed = nullptr);

  std::mt19937_64& rng() { return rng_; }

 private:
  size_t pick(size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng_); }
  template <class T>
  const T& pickFrom(const std::vector<T>& v) {
    return v[pick(v.size())];
  }

  std::mt19937_64 rng_;
};

}  // namespace anode::fuzz
