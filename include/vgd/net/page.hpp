#pragma once
// The browser page vgd-server serves at / (page.cpp): the job list and a
// job's drape drawn live with three.js from its frames' WebSocket.
#include <string_view>

namespace vgd::net {

std::string_view browser_page();

}  // namespace vgd::net
