// The versions of the libraries the executable runs with (for --version and
// the run record).
#pragma once

#include "io/run_record.h"

namespace pt {

SoftwareVersions software_versions();

}  // namespace pt
