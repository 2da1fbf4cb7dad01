# Build time only: link with GNU gold, which comes with binutils (build-essential) on every
# Debian machine, when the toolchain takes it. The default linker (bfd) spent about 10 % of a
# clean build's CPU on the package's ~85 links; gold links the same objects 3-4x faster
# (docs/validation/performance.md). TLC_GOLD_LINKER=OFF links with the toolchain's default.
option(TLC_GOLD_LINKER "Link with GNU gold when the toolchain supports it (build time only)" ON)
if(TLC_GOLD_LINKER AND NOT CMAKE_VERSION VERSION_LESS 3.18)
  include(CheckLinkerFlag)
  check_linker_flag(CXX "-fuse-ld=gold" TLC_HAVE_GOLD_LINKER)
  if(TLC_HAVE_GOLD_LINKER)
    add_link_options(-fuse-ld=gold)
  endif()
endif()
