#!/usr/bin/env bash
# expect.sh CODES REGEX COMMAND...   runs COMMAND and passes when it exits with one of
# CODES (e.g. 0, or 0,1) and its combined output matches the extended regex REGEX and
# holds no "nan" or "inf".
code=$1 regex=$2
shift 2
out=$("$@" 2>&1)
got=$?
printf '%s\n' "$out"
case ",$code," in *",$got,"*) ;; *) echo "expect.sh: exit code $got, expected $code" >&2; exit 1 ;; esac
if ! printf '%s\n' "$out" | grep -Eq -- "$regex"; then echo "expect.sh: output does not match /$regex/" >&2; exit 1; fi
if printf '%s\n' "$out" | grep -Eiq -- '(^|[^a-z])(nan|-?inf)([^a-z]|$)'; then echo "expect.sh: output holds nan or inf" >&2; exit 1; fi
exit 0
