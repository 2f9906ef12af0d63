# bash completion for lantern (installed as
# share/bash-completion/completions/lantern by `cmake --install`).
_lantern() {
  local cur prev words cword
  _init_completion || return
  local subcommands="render view compare merge info"
  local render_opts="-o --output --spp --time --target-error --adaptive --integrator --vcm-radius --vcm-alpha --roulette --light-subpaths --merging --mis --guide
    --spectral --maxdepth --threads --seed --sampler --light-sampler --resolution --cropwindow --pixelbounds --pixel --rays --wave-size
    --progress-interval --write-partial-images --log-level --log-file --stats --dump-rays --strategies --checkpoint --checkpoint-file --resume --keep-checkpoint --texture-cache --texture-dir --trace
    --trace-waves --part --display-server -q --quiet --help"
  local view_opts="--spp --time --target-error --adaptive --integrator --vcm-radius --vcm-alpha --roulette --light-subpaths --merging --mis --guide --spectral
    --maxdepth --threads --seed --sampler --light-sampler --resolution --cropwindow --pixelbounds --pixel --rays --wave-size --screenshot --exposure
    --texture-cache --texture-dir --help"
  local sub=""
  local i
  for ((i = 1; i < cword; ++i)); do
    case "${words[i]}" in render | view | compare | merge | info) sub=${words[i]}; break ;; esac
  done
  case "$prev" in
    --integrator) COMPREPLY=($(compgen -W "path bdpt lt vcm bpm ppm directlighting" -- "$cur")); return ;;
    --sampler) COMPREPLY=($(compgen -W "zsobol paddedsobol sobol halton stratified independent" -- "$cur")); return ;;
    --light-sampler) COMPREPLY=($(compgen -W "bvh power uniform" -- "$cur")); return ;;
    --mis) COMPREPLY=($(compgen -W "power balance" -- "$cur")); return ;;
    --merging) COMPREPLY=($(compgen -W "auto on" -- "$cur")); return ;;
    --rays) COMPREPLY=($(compgen -W "stream stream-1m single packet16" -- "$cur")); return ;;
    --log-level) COMPREPLY=($(compgen -W "error warning info verbose" -- "$cur")); return ;;
    -o | --output | --stats | --trace | --dump-rays | --checkpoint-file | --error-image | --screenshot | --log-file)
      _filedir; return ;;
    --strategies | --texture-dir) _filedir -d; return ;;
  esac
  if [ -z "$sub" ]; then
    COMPREPLY=($(compgen -W "$subcommands --version --help" -- "$cur"))
    return
  fi
  if [[ "$cur" == -* ]]; then
    case "$sub" in
      render) COMPREPLY=($(compgen -W "$render_opts" -- "$cur")) ;;
      view) COMPREPLY=($(compgen -W "$view_opts" -- "$cur")) ;;
      compare) COMPREPLY=($(compgen -W "--json --error-image --error-scale --help" -- "$cur")) ;;
      merge) COMPREPLY=($(compgen -W "-o --output --preview -q --quiet --help" -- "$cur")) ;;
      info) COMPREPLY=($(compgen -W "--help" -- "$cur")) ;;
    esac
    return
  fi
  case "$sub" in
    render | view) _filedir pbrt ;;
    *) _filedir ;;
  esac
}
complete -F _lantern lantern
