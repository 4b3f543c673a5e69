// A temporary folder for experiment tests, removed with everything in it.
#pragma once

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace dp::test {

class ExperimentTempDir {
 public:
  ExperimentTempDir() {
    std::random_device rd;
    m_dir = std::filesystem::temp_directory_path() / ("dp_experiment_test_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(m_dir);
  }
  ~ExperimentTempDir() {
    std::error_code ec;
    std::filesystem::remove_all(m_dir, ec);
  }
  ExperimentTempDir(const ExperimentTempDir&) = delete;
  ExperimentTempDir& operator=(const ExperimentTempDir&) = delete;

  std::string path(const std::string& name) const { return (m_dir / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(m_dir / name, std::ios::binary) << text;
    return path(name);
  }

 private:
  std::filesystem::path m_dir;
};

}  // namespace dp::test
