#include "vgd/high/top.hpp"  // upstream: refused
