// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "objif/dictionary.h"

using objif::Access;
using objif::Address;
using objif::Descriptor;
using objif::Entry;
using objif::ObjectInfo;
using objif::Status;
using objif::Value;
using objif::ValueType;

namespace {

// A small module exercising every column of the table: ranges, access kinds,
// an index range, a state rule in a hook and a handle-discarding command.
class TestModule : public objif::TableModule<TestModule> {
public:
    std::int32_t bus() const noexcept override { return 42; }
    std::string_view name() const noexcept override { return "test"; }
    bool present() const noexcept override { return present_; }

    std::span<const Entry<TestModule>> table() const noexcept { return kTable; }

    bool present_ = true;
    bool locked = false;
    std::int32_t level = 3;
    double gain = 0.5;
    std::array<std::int32_t, 4> per_index{};
    std::int32_t command_count = 0;

    void clean() { discard_handles(); }

private:
    Status read_level(const ObjectInfo&, const Address&, Value& v) { v = Value::of_int(level); return Status::kOk; }
    Status write_level(const ObjectInfo&, const Address&, const Value& v) {
        if (locked) return Status::kWrongDeviceState;  // the state rule lives in the hook
        level = v.as_int();
        return Status::kOk;
    }
    Status read_gain(const ObjectInfo&, const Address&, Value& v) { v = Value::of_double(gain); return Status::kOk; }
    Status write_gain(const ObjectInfo&, const Address&, const Value& v) { gain = v.as_double(); return Status::kOk; }
    Status read_version(const ObjectInfo&, const Address&, Value& v) { v = Value::of_int(7); return Status::kOk; }
    Status write_command(const ObjectInfo&, const Address&, const Value&) { ++command_count; return Status::kOk; }
    Status read_slot(const ObjectInfo&, const Address& a, Value& v) { v = Value::of_int(per_index[a.index]); return Status::kOk; }
    Status write_slot(const ObjectInfo&, const Address& a, const Value& v) { per_index[a.index] = v.as_int(); return Status::kOk; }
    Status write_clean(const ObjectInfo&, const Address&, const Value&) { discard_handles(); return Status::kOk; }

    static constexpr std::array<Entry<TestModule>, 6> kTable{{
        {{0, 1, 1, 0, "Level", ValueType::kInt32, Access::kReadWrite, 0, 10, Value::of_int(3), "test", {}, {}},
         &TestModule::read_level, &TestModule::write_level},
        {{0, 2, 2, 0, "Gain", ValueType::kDouble, Access::kReadWrite, -1.0, 1.0, Value::of_double(0.5), "test", {}, {}},
         &TestModule::read_gain, &TestModule::write_gain},
        {{0, 3, 3, 0, "Version", ValueType::kInt32, Access::kRead, objif::kInt32Min, objif::kInt32Max, Value::of_int(7), "test", {}, {}},
         &TestModule::read_version, nullptr},
        {{0, 4, 4, 0, "Command", ValueType::kInt32, Access::kWrite, objif::kInt32Min, objif::kInt32Max, Value::of_int(0), "test", {}, {}},
         nullptr, &TestModule::write_command},
        {{1, 0, 3, 5, "Slot", ValueType::kInt32, Access::kReadWrite, objif::kInt32Min, objif::kInt32Max, Value::of_int(0), "test", {}, {}},
         &TestModule::read_slot, &TestModule::write_slot},
        {{0, 9, 9, 0, "Clean", ValueType::kInt32, Access::kWrite, 1, 1, Value::of_int(1), "test", {}, {}},
         nullptr, &TestModule::write_clean},
    }};
};

class DictionaryTest : public ::testing::Test {
protected:
    void SetUp() override { ASSERT_EQ(dict.add(&mod), Status::kOk); }
    static Descriptor at(int bus, int dev, int idx, int sub) { return Descriptor{{bus, dev, idx, sub}, 0}; }
    TestModule mod;
    objif::Dictionary dict;
};

TEST_F(DictionaryTest, ReadWriteRoundTripAndHandleIsCached) {
    auto d = at(42, 0, 1, 0);
    EXPECT_EQ(dict.write(d, Value::of_int(9)), Status::kOk);
    EXPECT_NE(d.handle, objif::kNoHandle);
    const auto h = d.handle;
    Value v;
    EXPECT_EQ(dict.read(d, ValueType::kInt32, v), Status::kOk);
    EXPECT_EQ(v, Value::of_int(9));
    EXPECT_EQ(d.handle, h);
}

TEST_F(DictionaryTest, SameAddressGetsSameHandle) {
    auto a = at(42, 0, 1, 0), b = at(42, 0, 1, 0), c = at(42, 0, 2, 0);
    Value v;
    ASSERT_EQ(dict.read(a, ValueType::kInt32, v), Status::kOk);
    ASSERT_EQ(dict.read(b, ValueType::kInt32, v), Status::kOk);
    ASSERT_EQ(dict.read(c, ValueType::kDouble, v), Status::kOk);
    EXPECT_EQ(a.handle, b.handle);
    EXPECT_NE(a.handle, c.handle);
}

TEST_F(DictionaryTest, CheckOrderBusBeforeEverything) {
    auto d = at(43, 0, 1, 0);
    EXPECT_EQ(dict.write(d, Value::of_double(NAN)), Status::kNoSuchDevice);
}

TEST_F(DictionaryTest, CheckOrderDeviceThenIndexThenSub) {
    auto dev = at(42, 7, 1, 0);
    auto idx = at(42, 0, 99, 0);
    auto sub = at(42, 0, 1, 5);
    Value v;
    EXPECT_EQ(dict.read(dev, ValueType::kInt32, v), Status::kNoSuchDevice);
    EXPECT_EQ(dict.read(idx, ValueType::kInt32, v), Status::kObjectMissing);
    EXPECT_EQ(dict.read(sub, ValueType::kInt32, v), Status::kSubMissing);
    EXPECT_EQ(dev.handle, objif::kNoHandle) << "no handle for an object that does not exist";
}

TEST_F(DictionaryTest, CheckOrderAccessBeforeTypeAndRange) {
    auto ro = at(42, 0, 3, 0);
    EXPECT_EQ(dict.write(ro, Value::of_double(1e99)), Status::kReadOnly);
    auto wo = at(42, 0, 4, 0);
    Value v;
    EXPECT_EQ(dict.read(wo, ValueType::kDouble, v), Status::kWriteOnly);
}

TEST_F(DictionaryTest, CheckOrderTypeBeforeRange) {
    auto d = at(42, 0, 1, 0);
    EXPECT_EQ(dict.write(d, Value::of_double(1e99)), Status::kTypeMismatch);
    Value v;
    EXPECT_EQ(dict.read(d, ValueType::kDouble, v), Status::kTypeMismatch);
}

TEST_F(DictionaryTest, CheckOrderRangeBeforeState) {
    mod.locked = true;
    auto d = at(42, 0, 1, 0);
    EXPECT_EQ(dict.write(d, Value::of_int(11)), Status::kValueTooHigh);
    EXPECT_EQ(dict.write(d, Value::of_int(-1)), Status::kValueTooLow);
    EXPECT_EQ(dict.write(d, Value::of_int(5)), Status::kWrongDeviceState);
    EXPECT_EQ(mod.level, 3);
}

TEST_F(DictionaryTest, RangeIsInclusive) {
    auto d = at(42, 0, 1, 0);
    EXPECT_EQ(dict.write(d, Value::of_int(0)), Status::kOk);
    EXPECT_EQ(dict.write(d, Value::of_int(10)), Status::kOk);
    EXPECT_EQ(mod.level, 10);
}

TEST_F(DictionaryTest, NanAndInfinityAreRefusedWithoutStateChange) {
    auto d = at(42, 0, 2, 0);
    EXPECT_EQ(dict.write(d, Value::of_double(std::numeric_limits<double>::quiet_NaN())), Status::kInvalidValue);
    EXPECT_EQ(dict.write(d, Value::of_double(std::numeric_limits<double>::infinity())), Status::kInvalidValue);
    EXPECT_EQ(dict.write(d, Value::of_double(-std::numeric_limits<double>::infinity())), Status::kInvalidValue);
    EXPECT_EQ(mod.gain, 0.5);
}

TEST_F(DictionaryTest, IndexRangeRowServesEachIndex) {
    for (int i = 0; i <= 3; ++i) {
        auto d = at(42, 1, i, 5);
        EXPECT_EQ(dict.write(d, Value::of_int(100 + i)), Status::kOk);
    }
    for (int i = 0; i <= 3; ++i) EXPECT_EQ(mod.per_index[i], 100 + i);
    auto outside = at(42, 1, 4, 5);
    EXPECT_EQ(dict.write(outside, Value::of_int(1)), Status::kObjectMissing);
}

TEST_F(DictionaryTest, AbsentModuleAnswersNoSuchDevice) {
    mod.present_ = false;
    auto d = at(42, 0, 1, 0);
    Value v;
    EXPECT_EQ(dict.read(d, ValueType::kInt32, v), Status::kNoSuchDevice);
}

TEST_F(DictionaryTest, DiscardedHandleIsStaleUntilZeroed) {
    auto level = at(42, 0, 1, 0);
    Value v;
    ASSERT_EQ(dict.read(level, ValueType::kInt32, v), Status::kOk);
    auto clean = at(42, 0, 9, 0);
    ASSERT_EQ(dict.write(clean, Value::of_int(1)), Status::kOk);
    EXPECT_EQ(dict.read(level, ValueType::kInt32, v), Status::kStaleHandle);
    EXPECT_EQ(dict.write(level, Value::of_int(4)), Status::kStaleHandle);
    EXPECT_EQ(mod.level, 3) << "a stale handle changes nothing";
    // The command's own handle is stale too.
    EXPECT_EQ(dict.write(clean, Value::of_int(1)), Status::kStaleHandle);
    level.handle = objif::kNoHandle;
    EXPECT_EQ(dict.read(level, ValueType::kInt32, v), Status::kOk);
    EXPECT_NE(level.handle, objif::kNoHandle);
}

TEST_F(DictionaryTest, HandleNeverIssuedIsStale) {
    auto d = at(42, 0, 1, 0);
    d.handle = 0x00010077;
    Value v;
    EXPECT_EQ(dict.read(d, ValueType::kInt32, v), Status::kStaleHandle);
}

TEST_F(DictionaryTest, HandleOfAnotherObjectIsAMismatch) {
    auto level = at(42, 0, 1, 0);
    auto gain = at(42, 0, 2, 0);
    Value v;
    ASSERT_EQ(dict.read(level, ValueType::kInt32, v), Status::kOk);
    gain.handle = level.handle;
    EXPECT_EQ(dict.write(gain, Value::of_double(0.25)), Status::kHandleMismatch);
    EXPECT_EQ(mod.gain, 0.5);
}

TEST_F(DictionaryTest, WriteOnlyCommandRunsItsHook) {
    auto d = at(42, 0, 4, 0);
    EXPECT_EQ(dict.write(d, Value::of_int(-5)), Status::kOk);
    EXPECT_EQ(mod.command_count, 1);
}

TEST_F(DictionaryTest, DuplicateBusIsRefused) {
    TestModule other;
    EXPECT_EQ(dict.add(&other), Status::kInvalidArgument);
    EXPECT_EQ(dict.add(nullptr), Status::kInvalidArgument);
}

// A module whose find() returns nothing without naming why: the dictionary
// still refuses the access (ObjectMissing) and never calls the module's hooks.
class SilentModule : public TestModule {
public:
    std::int32_t bus() const noexcept override { return 43; }
    const objif::ObjectInfo* find(const objif::Address&, Status&) const noexcept override {
        return nullptr;
    }
};

TEST_F(DictionaryTest, ModuleThatFindsNothingWithoutAReasonIsStillRefused) {
    SilentModule silent;
    ASSERT_EQ(dict.add(&silent), Status::kOk);
    auto r = at(43, 0, 1, 0);
    Value v = Value::of_int(77);
    EXPECT_EQ(dict.read(r, ValueType::kInt32, v), Status::kObjectMissing);
    EXPECT_EQ(v, Value::of_int(77));
    auto w = at(43, 0, 1, 0);
    EXPECT_EQ(dict.write(w, Value::of_int(9)), Status::kObjectMissing);
    EXPECT_EQ(silent.level, 3);  // its default: no hook ran
    EXPECT_EQ(w.handle, objif::kNoHandle);
}

TEST_F(DictionaryTest, TableIsListable) {
    ASSERT_EQ(mod.object_count(), 6u);
    EXPECT_EQ(mod.object_at(0).name, "Level");
    EXPECT_EQ(mod.object_at(5).name, "Clean");
}

}  // namespace
