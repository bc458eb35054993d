#pragma once
// Files a model names (textures, material libraries), found as the tools
// that wrote them meant: paths written on Windows, with backslashes and
// in a case the disk does not have.
#include <filesystem>
#include <string>

namespace mvr {

// The file `written` names from dir: as written; else with backslashes
// read as slashes and each part matched without regard to case; else its
// file name alone, in dir (a path from the machine that wrote the model).
// Empty where nothing matches. `how` names the file found where it was
// not as written; `backslashes`, whether they were read.
std::string findFile(const std::filesystem::path& dir, const std::string& written, std::string& how, bool& backslashes);

// The file name's extension in lower case (".ply"): how the loaders pick a
// format.
std::string lowerExtension(const std::string& path);
std::string lowerCase(std::string s);

}  // namespace mvr
