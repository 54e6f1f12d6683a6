"""Metric plugins: the interface and registry (:mod:`.base`), the built-in metrics (material
metrics without weights, text-image metrics from local weights, the MLLM judge)."""
