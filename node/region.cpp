#include "node/region.h"
