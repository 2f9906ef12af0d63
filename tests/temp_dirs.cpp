// Tests write their files under the system's temporary folder, in folders
// named lantern-<what>-<process id>; each test process removes its own when
// it ends, so repeated runs leave nothing behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace {

class RemoveTemporaryFolders : public ::testing::Environment {
 public:
  void TearDown() override {
    namespace fs = std::filesystem;
    const std::string suffix = "-" + std::to_string(::getpid());
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(fs::temp_directory_path(), ec)) {
      const std::string name = e.path().filename().string();
      if (name.rfind("lantern-", 0) == 0 && name.size() > suffix.size() &&
          name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        fs::remove_all(e.path(), ec);
    }
  }
};

const auto* const kRegistered = ::testing::AddGlobalTestEnvironment(new RemoveTemporaryFolders);

}  // namespace
