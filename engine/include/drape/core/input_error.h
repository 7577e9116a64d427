#pragma once
// Errors in what the user gave us (files, settings, command lines). The message names the file and the
// element, e.g. "shirt.json: panel 'left_ftorso' edge 3: endpoint 9 out of range (panel has 7 vertices)".
#include <stdexcept>
#include <string>

namespace drape {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace drape
