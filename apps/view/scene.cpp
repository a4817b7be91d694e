#include "view/scene.h"

namespace strata::view {

void Scene::put(const std::string& id, Message message) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Entry& e = items_[id];
    if (e.version != 0) by_version_.erase(e.version);
    e.version = ++version_;
    e.message = std::move(message);
    e.removed = false;
    by_version_[e.version] = id;
  }
  notify();
}

void Scene::remove(const std::string& id) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = items_.find(id);
    if (it == items_.end() || it->second.removed) return;
    by_version_.erase(it->second.version);
    it->second.version = ++version_;
    it->second.message = encodeMessage({{"type", "remove"}, {"id", id}});
    it->second.removed = true;
    by_version_[it->second.version] = id;
  }
  notify();
}

std::uint64_t Scene::changesSince(std::uint64_t since, std::vector<Message>* out) const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = by_version_.upper_bound(since); it != by_version_.end(); ++it) {
    const Entry& e = items_.at(it->second);
    // A reader starting afresh does not need the removals of items it never saw.
    if (since == 0 && e.removed) continue;
    out->push_back(e.message);
  }
  return version_;
}

Message Scene::get(const std::string& id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = items_.find(id);
  return it == items_.end() || it->second.removed ? nullptr : it->second.message;
}

std::uint64_t Scene::version() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return version_;
}

std::size_t Scene::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::size_t n = 0;
  for (const auto& [id, e] : items_) n += e.removed ? 0 : 1;
  return n;
}

void Scene::setChangeListener(std::function<void()> listener) {
  std::lock_guard<std::mutex> lock(mutex_);
  listener_ = std::move(listener);
}

void Scene::notify() {
  std::function<void()> listener;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    listener = listener_;
  }
  if (listener) listener();
}

}  // namespace strata::view
