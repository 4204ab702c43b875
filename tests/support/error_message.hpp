// The message of the mixmesh::Error an action throws, for tests that check what a
// failure says; empty when it throws none.
#pragma once

#include <functional>
#include <string>

#include "mixmesh/core/error.hpp"

inline std::string error_message(const std::function<void()>& action) {
  try {
    action();
  } catch (const mixmesh::Error& error) {
    return error.what();
  }
  return "";
}
