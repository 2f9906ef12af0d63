// Loading a scene that must fail: an InputError whose message names every
// fragment (the file and line, what is wrong, what was expected).
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "lantern/scene.h"

namespace lantern {

inline void expect_load_error(const std::string& text, const std::string& filename,
                              std::initializer_list<const char*> fragments) {
  try {
    load_scene_from_string(text, filename, {});
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const InputError& e) {
    std::string msg = e.what();
    for (const char* f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "message \"" << msg << "\" lacks \"" << f << "\"";
  }
}

}  // namespace lantern
