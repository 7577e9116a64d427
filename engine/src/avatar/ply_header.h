#pragma once
// A plain reading of a PLY file's header before assimp reads it: assimp's PLY importer runs for minutes on a header
// without its end_header line (found by fuzz/fuzz_avatar.cpp), so such a file is refused first.
#include <cstddef>
#include <filesystem>
#include <string>

namespace drape::detail {

// Why the file's PLY header is unreadable, empty when it is not: the first line is not "ply" (a file named .ply), no
// "end_header" line comes within the first kMaxPlyHeaderBytes, or an element declares more items than the file has
// bytes. A file of another name whose first line is "ply" is checked too: assimp reads it as PLY by its content.
std::string plyHeaderProblem(const std::filesystem::path& file, bool namedPly);

constexpr std::size_t kMaxPlyHeaderBytes = 65536;

}  // namespace drape::detail
