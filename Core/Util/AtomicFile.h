// Files are written under a temporary name and renamed, so a crash never leaves a half file.
#pragma once

#include <functional>
#include <string>

namespace anode {

// Whether a file must be on the disk when writeAtomically returns (fsync of the file before its
// rename and of its directory after), as a checkpoint must be before an older one is removed.
enum class Durability { Buffered, Synced };

// Calls write(temporaryPath), then renames it to `path`. Throws std::runtime_error on failure.
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write,
                     Durability durability = Durability::Buffered);
// fsync of a file or a directory that exists (a directory: the names it holds).
void syncToDisk(const std::string& path);
// Writes `content` to `path` atomically.
void writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace anode
