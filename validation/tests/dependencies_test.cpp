// Every dependency of the design card links and does its job on this machine: FFTW in all three
// precisions with threads, Ceres, OpenImageIO (an EXR round trip), Vulkan with a glslc-compiled
// shader on a real device (lavapipe in CI). A build that "finds" a library it cannot use fails
// here, not in a later feature.
#include <ceres/ceres.h>
#include <fftw3.h>
#include <gtest/gtest.h>
#ifndef SWELL_WITHOUT_VULKAN
#include <vulkan/vulkan.h>
#endif

#include <OpenImageIO/imageio.h>
#include <cmath>
#include <complex>
#include <cstring>
#include <iostream>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <type_traits>
#include <utility>
#include <vector>

namespace {

// FFTW's forward transform of e^(2πi·3n/8) is 8 at bin 3 and 0 elsewhere, to a few ε of the
// precision (input and transform both in that precision).
template <typename Complex, typename Plan, typename MakePlan, typename Execute, typename Destroy>
void expect_fftw_finds_one_tone(MakePlan make_plan, Execute execute, Destroy destroy, double tol) {
  constexpr int n = 8;
  using Real = std::remove_reference_t<decltype(std::declval<Complex&>()[0])>;
  std::vector<Complex> in(n), out(n);
  for (int i = 0; i < n; ++i) {
    const Real phase = 2 * std::numbers::pi_v<Real> * 3 * i / n;
    in[i][0] = std::cos(phase);
    in[i][1] = std::sin(phase);
  }
  Plan plan = make_plan(n, in.data(), out.data(), FFTW_FORWARD, FFTW_ESTIMATE);
  ASSERT_NE(plan, nullptr);
  execute(plan);
  destroy(plan);
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR(double(out[k][0]), k == 3 ? 8.0 : 0.0, tol) << "bin " << k;
    EXPECT_NEAR(double(out[k][1]), 0.0, tol) << "bin " << k;
  }
}

TEST(Dependencies, FftwDoubleFloatLongDoubleAndThreads) {
  ASSERT_NE(fftw_init_threads(), 0);
  ASSERT_NE(fftwf_init_threads(), 0);
  fftw_plan_with_nthreads(2);
  expect_fftw_finds_one_tone<fftw_complex, fftw_plan>(fftw_plan_dft_1d, fftw_execute,
                                                      fftw_destroy_plan, 1e-14);
  expect_fftw_finds_one_tone<fftwf_complex, fftwf_plan>(fftwf_plan_dft_1d, fftwf_execute,
                                                        fftwf_destroy_plan, 1e-5);
  expect_fftw_finds_one_tone<fftwl_complex, fftwl_plan>(fftwl_plan_dft_1d, fftwl_execute,
                                                        fftwl_destroy_plan, 1e-17);  // 64-bit mantissa: ε ≈ 1e-19
  fftw_cleanup_threads();
  fftwf_cleanup_threads();
}

// Ceres fits y = e^(m x + c) to noiseless data and recovers m and c.
struct ExponentialResidual {
  double x, y;
  template <typename T>
  bool operator()(const T* m, const T* c, T* residual) const {
    residual[0] = y - exp(m[0] * x + c[0]);
    return true;
  }
};

TEST(Dependencies, CeresRecoversExponentialFit) {
  double m = 0, c = 0;
  ceres::Problem problem;
  for (int i = 0; i < 20; ++i) {
    const double x = 0.1 * i;
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<ExponentialResidual, 1, 1, 1>(
            new ExponentialResidual{x, std::exp(0.3 * x + 0.1)}),
        nullptr, &m, &c);
  }
  ceres::Solver::Options options;
  options.function_tolerance = 1e-14;
  options.parameter_tolerance = 1e-14;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  ASSERT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
  EXPECT_NEAR(m, 0.3, 1e-8);
  EXPECT_NEAR(c, 0.1, 1e-8);
}

TEST(Dependencies, OpenImageIoExrRoundTrip) {
  const auto path = std::filesystem::temp_directory_path() / "swell_dependencies_test.exr";
  const int width = 5, height = 3;
  std::vector<float> pixels(width * height);
  for (int i = 0; i < width * height; ++i) pixels[i] = 0.25f * i - 1.0f;
  {
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    const OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << out->geterror();
    out->close();
  }
  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->spec().width, width);
  EXPECT_EQ(in->spec().height, height);
  std::vector<float> back(width * height);
  ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, back.data()));
  in->close();
  EXPECT_EQ(back, pixels);  // float EXR channels are stored exactly
  std::filesystem::remove(path);
}

#ifndef SWELL_WITHOUT_VULKAN
std::vector<char> read_binary(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

TEST(Dependencies, VulkanDeviceAcceptsGlslcShader) {
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "swell dependency test";
  app.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  create.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateInstance(&create, nullptr, &instance), VK_SUCCESS)
      << "no Vulkan loader/driver: install mesa-vulkan-drivers (lavapipe)";
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  ASSERT_GE(count, 1u) << "no Vulkan device: install mesa-vulkan-drivers (lavapipe)";
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(devices[0], &properties);
  std::cout << "Vulkan device: " << properties.deviceName << "\n";

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{};
  queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue.queueFamilyIndex = 0;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  VkDeviceCreateInfo device_info{};
  device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue;
  VkDevice device = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateDevice(devices[0], &device_info, nullptr, &device), VK_SUCCESS);

  const auto spirv = read_binary(SWELL_SMOKE_SHADER_SPV);
  ASSERT_GT(spirv.size(), 20u) << "glslc output missing: " << SWELL_SMOKE_SHADER_SPV;
  ASSERT_EQ(spirv.size() % 4, 0u);
  std::vector<uint32_t> words(spirv.size() / 4);
  std::memcpy(words.data(), spirv.data(), spirv.size());
  EXPECT_EQ(words[0], 0x07230203u);  // SPIR-V magic number
  VkShaderModuleCreateInfo module_info{};
  module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  module_info.codeSize = spirv.size();
  module_info.pCode = words.data();
  VkShaderModule module = VK_NULL_HANDLE;
  EXPECT_EQ(vkCreateShaderModule(device, &module_info, nullptr, &module), VK_SUCCESS);
  vkDestroyShaderModule(device, module, nullptr);
  vkDestroyDevice(device, nullptr);
  vkDestroyInstance(instance, nullptr);
}
#endif

}  // namespace
