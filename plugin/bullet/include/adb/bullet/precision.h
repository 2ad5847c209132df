// The precision guard: every public adb::bullet header includes this, so a translation unit
// that sees Bullet at another precision than the one adb::bullet was built for fails to
// compile, instead of linking in part and corrupting memory at run time.
#pragma once

#include <LinearMath/btScalar.h>

#include "adb/bullet/config.h"

static_assert((sizeof(btScalar) == sizeof(double)) == (ADB_BULLET_DOUBLE_PRECISION != 0),
              "adb::bullet was built against Bullet at another precision than this translation "
              "unit uses: define BT_USE_DOUBLE_PRECISION (bullet-float64) exactly when "
              "adb::bullet was configured with ADB_BULLET_DOUBLE=ON");
