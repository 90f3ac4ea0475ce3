// SPDX-License-Identifier: MIT
// The words of the object interface each module's table (board, TC, 3D, OTC, temperature) is
// written in: its entries, their access, type, hooks and the statuses they answer.
#pragma once

#include "objif/dictionary.h"

namespace rwmos {

using objif::Access;
using objif::Address;
using objif::Entry;
using objif::Hooks;
using objif::ObjectInfo;
using objif::Status;
using objif::Value;
using objif::ValueType;

}  // namespace rwmos
