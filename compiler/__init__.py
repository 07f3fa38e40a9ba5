"""Inference: from a typed example to a DPO graph grammar (Merrell 2023, §4-5)."""
