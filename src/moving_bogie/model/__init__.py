"""The model: parameters (dimensionless and SI), Table 1 cases, parameter files."""
