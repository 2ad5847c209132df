// Text from a file, fit to quote in an error message: what every reader of users' files (mesh
// files here, scene files in adb::scene) uses when it names what it found.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace adb::io {

/// `text` with control bytes shown as '?', cut after `maxBytes` (at a character boundary) with
/// a note of how much was left out. A damaged file can put megabytes into what a reader quotes:
/// assimp's number parser quotes the rest of the file after the bad number.
std::string excerpt(std::string_view text, std::size_t maxBytes = 200);

/// excerpt() of a word from a file, in single quotes.
std::string quoted(std::string_view word);

}  // namespace adb::io
