#pragma once
// A current headless GL context for a test. The test is skipped only when EGL offers no display
// at all; any other failure (no GL 4.3 core context) fails it. A macro, because GTEST_SKIP and
// ASSERT must return from the test body or SetUp that uses it.
#include <gtest/gtest.h>

#include <string>

#include "render/gl_context.h"

#define RTSPH_HEADLESS_CONTEXT_OR_SKIP(ctx)                                 \
  do {                                                                     \
    std::string gl_error_;                                                 \
    bool no_display_ = false;                                              \
    (ctx) = ::rtsph::render::HeadlessContext::create(&gl_error_, &no_display_); \
    if (!(ctx) && no_display_) GTEST_SKIP() << gl_error_;                  \
    ASSERT_TRUE(ctx) << gl_error_;                                         \
  } while (0)
