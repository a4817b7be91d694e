#include "private_network.h"

#include <sched.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "child_process.h"
#include "strata/core/error.h"

namespace strata::bench {
namespace {

void runIp(const std::vector<std::string>& args) {
  int code = 127;
  try {
    code = waitProcess(spawnProcess("/usr/sbin/ip", args));
  } catch (const Error& e) {
    throw InputError(std::string("the private network needs iproute2's ip: ") + e.what());
  }
  std::string line = "ip";
  for (const std::string& a : args) line += " " + a;
  if (code != 0) throw InputError("'" + line + "' failed in the private network namespace");
}

}  // namespace

void enterPrivateNetwork() {
  if (unshare(CLONE_NEWNET) != 0) {
    throw InputError(std::string("unshare(CLONE_NEWNET) failed (root needed): ") +
                     std::strerror(errno));
  }
  runIp({"link", "set", "lo", "up"});
  runIp({"route", "add", "224.0.0.0/4", "dev", "lo"});
}

}  // namespace strata::bench
