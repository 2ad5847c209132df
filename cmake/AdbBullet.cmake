# Bullet as Debian ships it (3.24): single precision (bullet.pc) or double precision
# (bullet-float64.pc, which adds -DBT_USE_DOUBLE_PRECISION). Through pkg-config, because
# Debian's BulletConfig.cmake has no imported targets and CMake's FindBullet knows only single
# precision. The plugin must be compiled with the precision of the Bullet it links: a mismatch
# links in part and corrupts memory silently, so the choice is recorded in a generated header
# that every public plugin header checks at compile time (adb/bullet/precision.h).
option(ADB_BULLET_DOUBLE "Build adb::bullet against Bullet's double-precision libraries" OFF)

find_package(PkgConfig REQUIRED)
if(ADB_BULLET_DOUBLE)
  set(ADB_BULLET_PC bullet-float64)
  set(ADB_BULLET_DOUBLE_PRECISION 1)
else()
  set(ADB_BULLET_PC bullet)
  set(ADB_BULLET_DOUBLE_PRECISION 0)
endif()
pkg_check_modules(ADB_BULLET REQUIRED IMPORTED_TARGET ${ADB_BULLET_PC})
message(STATUS "adb::bullet: Bullet ${ADB_BULLET_VERSION} (${ADB_BULLET_PC})")
