//! The codes `npr_abi::param_value` gives its refusals are diag's: the ABI
//! depends on no npr crate, so it names them itself, and this holds the
//! two equal.

#[test]
fn refusal_codes_are_diags() {
    use npr_abi::param_value::codes as abi_codes;
    use npr_diag::codes;
    assert_eq!(abi_codes::BAD_ARGUMENT_VALUE, codes::BAD_ARGUMENT_VALUE);
    assert_eq!(abi_codes::UNKNOWN_NAME, codes::UNKNOWN_NAME);
    assert_eq!(abi_codes::TYPE_MISMATCH, codes::TYPE_MISMATCH);
    assert_eq!(abi_codes::UNIT_MISMATCH, codes::UNIT_MISMATCH);
    assert_eq!(abi_codes::OUT_OF_RANGE, codes::OUT_OF_RANGE);
    assert_eq!(abi_codes::BAD_GRADIENT, codes::BAD_GRADIENT);
}
