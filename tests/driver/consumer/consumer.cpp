// SPDX-License-Identifier: MIT
#include <cstdio>

#include <apci/apci.hpp>

int main() {
    apci::Board board("emu:");
    auto plane = apci::object(APCI_TC_BUS, APCI_TC_DEVICE_INIT, APCI_TC_PLANE, 0);
    const auto r = board.read_int(plane);
    std::printf("TcPlane %d (%s)\n", r.value, apci_status_name(r.status));
    return r.ok() ? 0 : 1;
}
