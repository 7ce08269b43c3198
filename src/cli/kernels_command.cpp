// `sphstab kernels`: the kernel library with support, normalisation and inflection point.
#include <cstdio>

#include "commands.hpp"
#include "sphstab/kernel/kernel.hpp"

namespace sphstab::cli {

namespace {

template <int Dim>
void print_row(KernelType type, KernelScaling scaling) {
  Kernel<Dim> k(type, scaling);
  std::printf("%s,%d,%s,%.1f,%.12g,%s,%.12g\n", kernel_name(type).c_str(), Dim,
              scaling == KernelScaling::Support2h ? "support-2h" : "native", k.support_factor(), k.normalisation(),
              k.closed_form_normalisation() ? "closed-form" : "quadrature", k.inflection_q());
}

}  // namespace

void register_kernels_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("kernels", "List kernels: support radius/h, normalisation sigma_d, inflection q");
  auto native = std::make_shared<bool>(false);
  cmd->add_flag("--native", *native, "Use each kernel's native scaling instead of support 2h");
  cmd->callback([native] {
    std::printf("kernel,dim,scaling,support_over_h,sigma,normalisation,inflection_q\n");
    auto scaling = *native ? KernelScaling::Native : KernelScaling::Support2h;
    for (KernelType t : all_kernel_types()) {
      print_row<1>(t, scaling);
      print_row<2>(t, scaling);
      print_row<3>(t, scaling);
    }
  });
}

}  // namespace sphstab::cli
