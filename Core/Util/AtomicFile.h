// Files are written under a temporary name and renamed, so a crash never leaves a half file.
#pragma once

#include <functional>
#include <string>

namespace anode {

// Calls write(temporaryPath), then renames it to `path`. Throws std::runtime_error on failure.
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);
// Writes `content` to `path` atomically.
void writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace anode
