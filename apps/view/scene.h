#pragma once
// The viewer's scene: the latest message of every item (a mesh block, an object set, a pose, a
// trajectory, the ESDF slice, stats), each under an id. A writer replaces an item's message; a
// reader asks for what changed after the version it last read and gets each changed item's latest
// message once, in the order they changed. So a slow client never queues every update: it reads
// the state as it is when it is ready (what strata view's WebSocket sessions do).
// Thread safe: any thread may put, remove and read.
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "view/wire.h"

namespace strata::view {

class Scene {
 public:
  /// Sets the message of item `id` (replacing any earlier one) and calls the change listener.
  void put(const std::string& id, Message message);
  /// Removes item `id` (readers past it get a "remove" message for it); no-op when absent.
  void remove(const std::string& id);
  /// Appends to `out` the messages of the items changed after `since`, oldest change first, and
  /// returns the version the reader is then at. 0 reads everything.
  std::uint64_t changesSince(std::uint64_t since, std::vector<Message>* out) const;
  /// The current message of `id`, null when absent.
  Message get(const std::string& id) const;
  std::uint64_t version() const;
  std::size_t size() const;
  /// Called (on the writing thread, outside the scene's lock) after every put and remove.
  void setChangeListener(std::function<void()> listener);

 private:
  struct Entry {
    std::uint64_t version = 0;
    Message message;  // a "remove" message for a removed item
    bool removed = false;
  };
  void notify();

  mutable std::mutex mutex_;
  std::uint64_t version_ = 0;
  std::map<std::string, Entry> items_;
  std::map<std::uint64_t, std::string> by_version_;
  std::function<void()> listener_;
};

}  // namespace strata::view
