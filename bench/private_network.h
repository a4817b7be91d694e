#pragma once
// A network namespace of this process's own, for benchmarks whose processes talk over LCM's
// udpm:// (kernel multicast): nothing they send can leave the machine.

namespace strata::bench {

/// Moves the calling thread, the sockets it opens afterwards and the children it starts
/// afterwards into a new network namespace with loopback up and 224.0.0.0/4 routed to it.
/// Needs CAP_SYS_ADMIN (root) and `ip` (iproute2); throws InputError saying so otherwise.
/// NOTE: a namespace belongs to a thread: call it before opening LCM or starting children.
void enterPrivateNetwork();

}  // namespace strata::bench
