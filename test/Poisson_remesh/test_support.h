// Shared by the test files: where CGAL's data set is, a scratch folder, tiny file helpers.
#ifndef POISSON_REMESH_TEST_SUPPORT_H
#define POISSON_REMESH_TEST_SUPPORT_H

#include <filesystem>
#include <fstream>
#include <string>

namespace test_support {

/// A mesh of CGAL's data set, extracted by the build: data_mesh("meshes/fandisk.off").
inline std::string data_mesh(const std::string& name) { return std::string(POISSON_REMESH_DATA_DIR) + "/" + name; }

/// A fresh folder for files a test writes.
inline std::filesystem::path scratch_dir(const std::string& name)
{
  std::filesystem::path p = std::filesystem::temp_directory_path() / ("poisson_remesh_test_" + name);
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

inline std::string write_text(const std::filesystem::path& file, const std::string& content)
{
  std::ofstream(file, std::ios::binary) << content;
  return file.string();
}

inline std::string read_text(const std::filesystem::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

} // namespace test_support

#endif
