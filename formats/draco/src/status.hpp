#pragma once
// libdraco's status messages in our error style.

#include <draco/core/status.h>

#include <cctype>
#include <string>

namespace pdeface::draco {

//! "Failed to decode geometry data." -> "failed to decode geometry data".
inline std::string lowercase_message(const ::draco::Status& status) {
  std::string message = status.error_msg_string();
  if (!message.empty()) message[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(message[0])));
  while (!message.empty() && (message.back() == '.' || message.back() == ' '))
    message.pop_back();
  return message;
}

} // namespace pdeface::draco
