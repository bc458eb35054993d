#pragma once
// What a loader read other than as written, for Scene::warnings: each
// distinct warning once, prefixed with the file it is about.
#include <set>
#include <string>
#include <utility>

#include "mvr/scene.h"

namespace mvr {

class LoadWarnings {
 public:
  LoadWarnings(Scene& scene, std::string path) : scene_(scene), path_(std::move(path)) {}
  void operator()(const std::string& what) {
    if (said_.insert(what).second) scene_.warnings.push_back(path_ + ": " + what);
  }

 private:
  Scene& scene_;
  std::string path_;
  std::set<std::string> said_;
};

}  // namespace mvr
