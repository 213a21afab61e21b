# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The master-file workbench.

A local web page (server, page files) and its headless-browser driver.
"""
